// Validates a glTF binary (.glb) with the Khronos glTF-Validator (npm package gltf-validator,
// fetched into build/npm at configure time): prints the validator's errors and warnings and
// exits 0 when it found no error, 1 when it did, 2 when the file could not be validated.
//   NODE_PATH=build/npm/node_modules node tests/gltf_validate.js mesh.glb
'use strict';
const fs = require('fs');
const validator = require('gltf-validator');

const file = process.argv[2];
validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {maxIssues: 50}).then(
    (report) => {
      for (const m of report.issues.messages) {
        if (m.severity <= 1) console.log(`${file}: ${m.code} at ${m.pointer}: ${m.message}`);
      }
      console.log(`${file}: ${report.issues.numErrors} errors, ${report.issues.numWarnings} ` +
                  `warnings (glTF-Validator ${report.validatorVersion})`);
      process.exit(report.issues.numErrors === 0 ? 0 : 1);
    },
    (error) => {
      console.error(`${file}: not validated: ${error}`);
      process.exit(2);
    });
