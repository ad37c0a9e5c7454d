#!/usr/bin/env python3
"""Checks the layers of sewer3d (docs/architecture.md) over every source file.

Reads the targets CMake recorded (build/layers.txt: KIND TARGET FOLDER SOURCES... -- LINKED...)
and checks that
  - every module's files (headers included) include only headers of the module itself and of
    the modules it links, directly or through them;
  - a test links its own module and sewer3d_testing only, plus the simulator (sewer3d_sim,
    sewer3d_simio) when all its files are named *_sim_test.cpp (tests against rendered images
    or simulated runs), and includes accordingly (so may a header *_sim_test.hpp beside them,
    what several of them share);
  - nothing but the simulator's own modules (sim, simio), the programs and simulator tests
    reaches sim/: a capture run is processed without the renderer;
  - only tests link sewer3d_testing; module dependencies have no cycle;
  - every .cpp under src/sewer3d belongs to a target (else nothing would check it).

usage: check_layers.py LAYERS_TXT SOURCE_ROOT        exit 1 and one line per violation
       check_layers.py --self-test LAYERS_TXT SOURCE_ROOT
         shows that an added #include "sewer3d/sim/renderer.hpp" in io/ or triangulate/ fails
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*"sewer3d/([A-Za-z0-9_]+)/[^"]+"', re.M)
SIMULATOR = {"sim", "simio", "simeval"}


def read_layers(path):
    targets = []
    with open(path) as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            split = words.index("--")
            kind, target, folder = words[0], words[1], words[2]
            targets.append({"kind": kind, "target": target, "folder": folder,
                            "sources": words[3:split], "linked": words[split + 1:]})
    return targets


def closures(modules):
    """modules: name -> direct deps. Returns name -> set of modules reachable, or raises."""
    result = {}

    def visit(name, path):
        if name in result:
            return result[name]
        if name in path:
            raise ValueError("dependency cycle: " + " -> ".join(path + [name]))
        reach = set()
        for dep in modules.get(name, []):
            reach.add(dep)
            reach |= visit(dep, path + [name])
        result[name] = reach
        return reach

    for name in modules:
        visit(name, [])
    return result


def includes_of(path, injected):
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    found = INCLUDE.findall(text)
    return found + injected.get(os.path.normpath(path), [])


def check(layers_txt, root, injected=None):
    injected = {os.path.normpath(k): v for k, v in (injected or {}).items()}
    targets = read_layers(layers_txt)
    modules = {t["folder"]: t["linked"] for t in targets if t["kind"] == "module"}
    errors = []
    try:
        reach = closures(modules)
    except ValueError as e:
        return [str(e)]

    def allowed_for(names):
        out = set(names)
        for n in names:
            out |= reach.get(n, set())
        return out

    def check_file(path, allowed, who):
        for mod in includes_of(path, injected):
            if mod not in allowed:
                rel = os.path.relpath(path, root)
                errors.append(f"{rel}: includes sewer3d/{mod}/, which {who} may not use "
                              f"(allowed: {', '.join(sorted(allowed))})")

    src = os.path.join(root, "src", "sewer3d")
    owned = set()
    for t in targets:
        for s in t["sources"]:
            owned.add(os.path.normpath(os.path.join(root, s)))
    for name, deps in modules.items():
        if "testing" in deps:
            errors.append(f"module {name} links sewer3d_testing: only tests may")
        if name not in SIMULATOR | {"testing"} and "sim" in reach[name]:
            errors.append(f"module {name} reaches sim/ (through {', '.join(deps)}): the "
                          "processing chain must not link the renderer")
    for t in targets:
        folder = t["folder"]
        if t["kind"] == "module":
            allowed = allowed_for([folder])
            folder_path = os.path.join(src, folder)
            for f in sorted(os.listdir(folder_path)):
                if f.endswith(("_test.cpp")) or not f.endswith((".hpp", ".cpp", ".h")):
                    continue
                path = os.path.join(folder_path, f)
                if f.endswith("_sim_test.hpp"):  # support shared by the folder's sim tests
                    check_file(path, allowed_for([folder] + sorted(SIMULATOR)) | {"testing"},
                               f"sim tests of {folder}")
                    continue
                if f.endswith(".cpp") and os.path.normpath(path) not in owned:
                    errors.append(f"src/sewer3d/{folder}/{f}: in no target (add it to SOURCES)")
                check_file(path, allowed, f"module {folder}")
        elif t["kind"] == "test":
            extra = [m for m in t["linked"] if m not in (folder, "testing")]
            sim_test = all(s.endswith("_sim_test.cpp") for s in t["sources"])
            for m in extra:
                if not (m in SIMULATOR and sim_test):
                    errors.append(f"test {t['target']} links sewer3d_{m}: a test links its own "
                                  "module and sewer3d_testing (and sewer3d_sim or sewer3d_simio "
                                  "if it is a *_sim_test.cpp)")
            allowed = allowed_for([folder] + [m for m in extra if m in SIMULATOR]) | {"testing"}
            for s in t["sources"]:
                check_file(os.path.join(root, s), allowed, f"test {t['target']}")
        else:  # a program: its sources and the headers beside them
            allowed = allowed_for([folder] + t["linked"])
            for s in t["sources"]:
                check_file(os.path.join(root, s), allowed, f"program {t['target']}")
    for folder in sorted(os.listdir(src)):
        path = os.path.join(src, folder)
        if not os.path.isdir(path):
            continue
        for f in sorted(os.listdir(path)):
            p = os.path.normpath(os.path.join(path, f))
            if f.endswith(".cpp") and p not in owned:
                if f.endswith("_test.cpp") or folder not in modules:
                    errors.append(f"src/sewer3d/{folder}/{f}: in no target")
    return sorted(set(errors))


def self_test(layers_txt, root):
    """An include of the renderer added to io/ and triangulate/ must be reported, and only it."""
    baseline = set(check(layers_txt, root))
    probes = {os.path.join(root, "src/sewer3d/io/file_error.hpp"): ["sim"],
              os.path.join(root, "src/sewer3d/triangulate/dlt.cpp"): ["sim"]}
    found = set(check(layers_txt, root, probes)) - baseline
    ok = (len(found) == 2 and any("io/file_error.hpp: includes sewer3d/sim/" in e for e in found)
          and any("triangulate/dlt.cpp: includes sewer3d/sim/" in e for e in found))
    for e in sorted(found):
        print("caught:", e)
    print("self-test:", "passed" if ok else "FAILED: the injected includes were not both caught")
    return 0 if ok else 1


def main(argv):
    if len(argv) == 4 and argv[1] == "--self-test":
        return self_test(argv[2], argv[3])
    if len(argv) != 3:
        print(__doc__)
        return 2
    errors = check(argv[1], argv[2])
    for e in errors:
        print(e)
    print(f"layers: {len(errors)} violation(s)")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
