// The inspection's files: profile.csv and observations.json round trips (NaN as empty fields),
// readers that name the bad field, observations.csv's columns and quoting, and an ISYBAU-style
// XML that parses back (a small well-formedness check below: tags nest and close, one root,
// entities are the five XML ones) with the elements each observation should give.

#include "sewer3d/io/inspection_io.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

class InspectionIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sewer3d_inspection_io_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    files_ = InspectionFilesIn(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  InspectionFiles files_;
};

Profile SampleProfile() {
  Profile p;
  p.nominal_diameter_mm = 300.0;
  for (int i = 0; i < 3; ++i) {
    ProfileRow r;
    r.station_mm = 10.0 * i - 10.0;
    r.coverage = 0.95 + 0.01 * i;
    r.widest_gap_deg = 3.25;
    r.height_mm = 282.1234 + i;
    r.width_mm = 317.9876;
    r.circumference_mm = 943.2109;
    r.mean_diameter_mm = 300.2345;
    r.min_diameter_mm = 282.0001;
    r.max_diameter_mm = 318.0002;
    r.vertical_change_pct = -5.9589;
    r.horizontal_change_pct = 5.9959;
    r.ovality_en_pct = 6.0001;
    r.ovality_astm_pct = 5.9128;
    r.min_radius_mm = 141.0;
    r.mean_radius_mm = 150.0;
    r.max_radius_mm = 159.0;
    p.rows.push_back(r);
  }
  ProfileRow unmeasured;
  unmeasured.station_mm = 20.0;
  unmeasured.coverage = 0.4;
  unmeasured.widest_gap_deg = 120.0;
  unmeasured.height_mm = unmeasured.circumference_mm = unmeasured.ovality_astm_pct =
      std::numeric_limits<double>::quiet_NaN();
  p.rows.push_back(unmeasured);
  return p;
}

TEST_F(InspectionIoTest, ProfileCsvRoundTrip) {
  const Profile p = SampleProfile();
  WriteProfileCsv(files_.profile_csv, p);
  const std::string text = ReadTextFile(files_.profile_csv);
  EXPECT_EQ(text.rfind("station_m,coverage,widest_gap_deg,height_mm,", 0), 0u);
  EXPECT_NE(text.find("\n0.0200,0.4000,120.00,,0.0000,,"), std::string::npos) << text;
  const Profile q = ReadProfileCsv(files_.profile_csv);
  EXPECT_DOUBLE_EQ(q.nominal_diameter_mm, 300.0);
  ASSERT_EQ(q.rows.size(), p.rows.size());
  for (size_t i = 0; i < p.rows.size(); ++i) {
    const ProfileRow &a = p.rows[i], &b = q.rows[i];
    EXPECT_NEAR(b.station_mm, a.station_mm, 0.05);
    EXPECT_NEAR(b.coverage, a.coverage, 5e-5);
    EXPECT_NEAR(b.widest_gap_deg, a.widest_gap_deg, 0.005);
    for (const double ProfileRow::*f :
         {&ProfileRow::height_mm, &ProfileRow::width_mm, &ProfileRow::circumference_mm,
          &ProfileRow::mean_diameter_mm, &ProfileRow::min_diameter_mm, &ProfileRow::max_diameter_mm,
          &ProfileRow::vertical_change_pct, &ProfileRow::horizontal_change_pct,
          &ProfileRow::ovality_en_pct, &ProfileRow::ovality_astm_pct, &ProfileRow::min_radius_mm,
          &ProfileRow::mean_radius_mm, &ProfileRow::max_radius_mm}) {
      if (std::isnan(a.*f)) {
        EXPECT_TRUE(std::isnan(b.*f));
      } else {
        EXPECT_NEAR(b.*f, a.*f, 5e-5);
      }
    }
  }
}

TEST_F(InspectionIoTest, BadProfileCsvNamesLineAndField) {
  WriteProfileCsv(files_.profile_csv, SampleProfile());
  const std::string good = ReadTextFile(files_.profile_csv);
  const auto expect_error = [&](const std::string& from, const std::string& to,
                                const std::string& what) {
    std::string text = good;
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    WriteTextFile(files_.profile_csv, text.replace(at, from.size(), to));
    try {
      ReadProfileCsv(files_.profile_csv);
      ADD_FAILURE() << "no error for " << to;
    } catch (const FileError& e) {
      EXPECT_NE(std::string(e.what()).find(files_.profile_csv.string() + ": " + what),
                std::string::npos)
          << e.what();
    }
  };
  expect_error("282.1234", "282.12x", "line 2: height_mm '282.12x' is not a number");
  expect_error("0.0200,0.4000", "0.0200,1.4000", "line 5: coverage must be in 0..1");
  expect_error("0.0200,0.4000", "0.0000,0.4000", "line 5: station_m must increase");
  expect_error("0.0200,0.4000", ",0.4000", "line 5: station_m '' is not a number");
  expect_error("station_m,", "station_mm,", "line 1: header must be");
}

std::vector<Observation> SampleObservations() {
  Observation joint;
  joint.id = "O1";
  joint.code = "BAJ";
  joint.characterisation = "B";
  joint.station_mm = 420.04;
  joint.clock_h = 1.0;
  joint.clock_from_h = 0.5;
  joint.clock_to_h = 2.25;
  joint.at_joint = true;
  joint.confidence = 0.93;
  joint.quantities = {{"offset_mm", 6.1, "mm"}, {"gap_mm", 9.8, "mm"}};
  joint.crop = {2090, 60, 4600, 900};
  joint.remark = "joint offset 6.1 mm at 1 h, gap \"open\" & <clean>";
  Observation deposit;
  deposit.id = "O2";
  deposit.code = "BBC";
  deposit.station_mm = 700.0;
  deposit.length_mm = 150.0;
  deposit.clock_h = 6.0;
  deposit.clock_from_h = 5.0;
  deposit.clock_to_h = 7.0;
  deposit.confidence = 0.5;
  deposit.quantities = {{"height_mm", 12.0, "mm"}};
  deposit.crop = {3500, 750, 2000, 700};
  deposit.remark = "deposit, 12 mm";
  return {joint, deposit};
}

TEST_F(InspectionIoTest, ObservationsJsonRoundTrip) {
  const auto a = SampleObservations();
  WriteObservationsJson(files_.observations_json, a);
  const auto b = ReadObservationsJson(files_.observations_json);
  ASSERT_EQ(b.size(), a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(b[i].id, a[i].id);
    EXPECT_EQ(b[i].code, a[i].code);
    EXPECT_EQ(b[i].characterisation, a[i].characterisation);
    EXPECT_DOUBLE_EQ(b[i].station_mm, a[i].station_mm);
    EXPECT_DOUBLE_EQ(b[i].length_mm, a[i].length_mm);
    EXPECT_DOUBLE_EQ(b[i].clock_h, a[i].clock_h);
    EXPECT_DOUBLE_EQ(b[i].clock_from_h, a[i].clock_from_h);
    EXPECT_DOUBLE_EQ(b[i].clock_to_h, a[i].clock_to_h);
    EXPECT_EQ(b[i].at_joint, a[i].at_joint);
    EXPECT_DOUBLE_EQ(b[i].confidence, a[i].confidence);
    ASSERT_EQ(b[i].quantities.size(), a[i].quantities.size());
    for (size_t k = 0; k < a[i].quantities.size(); ++k) {
      EXPECT_EQ(b[i].quantities[k].name, a[i].quantities[k].name);
      EXPECT_DOUBLE_EQ(b[i].quantities[k].value, a[i].quantities[k].value);
      EXPECT_EQ(b[i].quantities[k].unit, a[i].quantities[k].unit);
    }
    EXPECT_EQ(b[i].crop.row0, a[i].crop.row0);
    EXPECT_EQ(b[i].crop.rows, a[i].crop.rows);
    EXPECT_EQ(b[i].crop.col0, a[i].crop.col0);
    EXPECT_EQ(b[i].crop.cols, a[i].crop.cols);
    EXPECT_EQ(b[i].remark, a[i].remark);
  }
  ASSERT_NE(b[0].Find("gap_mm"), nullptr);
  EXPECT_DOUBLE_EQ(b[0].Find("gap_mm")->value, 9.8);
}

TEST_F(InspectionIoTest, BadObservationsJsonNamesTheField) {
  WriteObservationsJson(files_.observations_json, SampleObservations());
  const std::string good = ReadTextFile(files_.observations_json);
  const auto expect_error = [&](const std::string& from, const std::string& to,
                                const std::string& field) {
    std::string text = good;
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    WriteTextFile(files_.observations_json, text.replace(at, from.size(), to));
    try {
      ReadObservationsJson(files_.observations_json);
      ADD_FAILURE() << "no error for " << to;
    } catch (const FileError& e) {
      EXPECT_NE(
          std::string(e.what()).find(files_.observations_json.string() + ": field '" + field + "'"),
          std::string::npos)
          << e.what();
    }
  };
  expect_error("\"clock_h\": 6.0", "\"clock_h\": 13.0", "observations[1].clock_h");
  expect_error("\"confidence\": 0.93", "\"confidence\": \"high\"", "observations[0].confidence");
  expect_error("\"at_joint\": true", "\"at_joint\": 1", "observations[0].at_joint");
  expect_error("\"unit\": \"mm\"", "\"units\": \"mm\"", "observations[0].quantities[0].units");
  expect_error("\"rows\": 750", "\"rows\": -750", "observations[1].crop.rows");
  expect_error("\"code\": \"BBC\"", "\"code\": \"\"", "observations[1].code");
  expect_error("\"code\": \"BBC\"", "\"code\": \"BBX\"", "observations[1].code");
  expect_error("\"version\": 1", "\"version\": 2", "version");
  expect_error("sewer3d-observations", "sewer3d-features", "format");
  expect_error("\"station_mm\": 700.0", "\"station_mm\": 1e308", "observations[1].station_mm");
  expect_error("\"id\": \"O2\"", "\"id\": \"O1\"", "observations[1].id");
  // A unit the name contradicts (a 4 mm offset read as 4 m), a characterisation BAJ has not.
  expect_error("\"unit\": \"mm\"", "\"unit\": \"m\"", "observations[0].quantities[0].unit");
  expect_error("\"characterisation\": \"B\"", "\"characterisation\": \"ZZ\"",
               "observations[0].characterisation");
  expect_error("\"characterisation\": \"B\"", "\"characterisation\": \"b\"",
               "observations[0].characterisation");
}

TEST_F(InspectionIoTest, ObservationsCsvHasOneQuotedLinePerObservation) {
  WriteObservationsCsv(files_.observations_csv, SampleObservations());
  std::istringstream in(ReadTextFile(files_.observations_csv));
  std::string header, first, second, extra;
  std::getline(in, header);
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_FALSE(std::getline(in, extra));
  EXPECT_EQ(header,
            "id,code,characterisation,station_m,length_m,clock_h,clock_from_h,clock_to_h,"
            "at_joint,confidence,q1_name,q1_value,q1_unit,q2_name,q2_value,q2_unit,remark");
  EXPECT_EQ(first,
            "O1,BAJ,B,0.42,0.000,1.00,0.50,2.25,1,0.93,offset_mm,6.100,mm,gap_mm,9.800,mm,"
            "\"joint offset 6.1 mm at 1 h, gap \"\"open\"\" & <clean>\"");
  EXPECT_EQ(second,
            "O2,BBC,,0.70,0.150,6.00,5.00,7.00,0,0.50,height_mm,12.000,mm,,,,\"deposit, 12 mm\"");
}

/// A minimal XML reader for the test: checks that tags nest and close under one root and that
/// only the five XML entities appear; returns each leaf element's path and text
/// ("Identifikation/Version" → "2017-07"), throws std::runtime_error when not well formed.
std::multimap<std::string, std::string> ParseXml(const std::string& xml) {
  std::multimap<std::string, std::string> leaves;
  std::vector<std::string> open;
  std::string text, path;
  int roots = 0;
  size_t i = 0;
  auto fail = [&](const std::string& why) {
    throw std::runtime_error(why + " at " + std::to_string(i));
  };
  auto joined = [&] {
    std::string p;
    for (const auto& name : open) p += (p.empty() ? "" : "/") + name;
    return p;
  };
  while (i < xml.size()) {
    if (xml[i] != '<') {
      if (xml[i] == '&') {
        const size_t end = xml.find(';', i);
        const std::string entity = xml.substr(i, end - i + 1);
        if (entity != "&amp;" && entity != "&lt;" && entity != "&gt;" && entity != "&quot;" &&
            entity != "&apos;")
          fail("unknown entity " + entity);
      }
      if (open.empty() && !std::isspace(static_cast<unsigned char>(xml[i])))
        fail("text outside the root");
      text += xml[i++];
      continue;
    }
    const size_t end = xml.find('>', i);
    if (end == std::string::npos) fail("unclosed tag");
    const std::string tag = xml.substr(i + 1, end - i - 1);
    i = end + 1;
    if (tag.front() == '?') continue;  // declaration
    if (tag.front() == '/') {
      if (open.empty() || open.back() != tag.substr(1)) fail("mismatched </" + tag.substr(1));
      if (text.find_first_not_of(" \n") != std::string::npos) leaves.emplace(joined(), text);
      open.pop_back();
      text.clear();
      continue;
    }
    const std::string name = tag.substr(0, tag.find(' '));
    if (open.empty()) ++roots;
    if (roots > 1) fail("second root");
    open.push_back(name);
    text.clear();
  }
  if (!open.empty() || roots != 1) fail("unclosed " + (open.empty() ? "" : open.back()));
  return leaves;
}

TEST_F(InspectionIoTest, IsybauXmlIsWellFormedWithOneConditionPerEntry) {
  IsybauHeader header;
  header.object_name = "demo & co";
  header.inspection_date = "2026-12-02";
  header.profile_height_mm = 300.0;
  header.profile_width_mm = 300.0;
  WriteObservationsIsybau(files_.observations_xml, SampleObservations(), header);
  const auto leaves = ParseXml(ReadTextFile(files_.observations_xml));
  const std::string anlage =
      "Identifikation/Datenkollektive/Zustandsdatenkollektiv/"
      "InspizierteAbwassertechnischeAnlage/";
  const std::string z = anlage + "OptischeInspektion/Rohrleitung/Inspektionsdaten/RZustand/";
  EXPECT_EQ(leaves.find(anlage + "Objektbezeichnung")->second, "demo &amp; co");
  EXPECT_EQ(leaves.find(anlage + "OptischeInspektion/Rohrleitung/RGrunddaten/Profilhoehe")->second,
            "300");
  // The joint is one entry, the deposit a start (A) and an end (B).
  EXPECT_EQ(leaves.count(z + "InspektionsKode"), 3u);
  EXPECT_EQ(leaves.count(z + "Station"), 3u);
  EXPECT_EQ(leaves.count(z + "Streckenschaden"), 2u);
  EXPECT_EQ(leaves.count(z + "Quantifizierung2Numerisch"), 1u);
  const auto values = [&](const std::string& name) {
    std::vector<std::string> v;
    for (auto [it, end] = leaves.equal_range(z + name); it != end; ++it) v.push_back(it->second);
    return v;
  };
  EXPECT_EQ(values("Station"), (std::vector<std::string>{"0.42", "0.70", "0.85"}));
  EXPECT_EQ(values("InspektionsKode"), (std::vector<std::string>{"BAJ", "BBC", "BBC"}));
  EXPECT_EQ(values("Charakterisierung1"), (std::vector<std::string>{"B"}));
  EXPECT_EQ(values("Verbindung"), (std::vector<std::string>{"1", "0", "0"}));
  EXPECT_EQ(values("Quantifizierung1Numerisch"),
            (std::vector<std::string>{"6.10", "12.00", "12.00"}));
  EXPECT_EQ(values("PositionVon"), (std::vector<std::string>{"01", "05", "05"}));  // 0.5 → 1
  EXPECT_EQ(values("PositionBis"), (std::vector<std::string>{"02", "07", "07"}));
  EXPECT_EQ(values("Streckenschaden"), (std::vector<std::string>{"A", "B"}));
  EXPECT_EQ(values("StreckenschadenLfdNr"), (std::vector<std::string>{"1", "1"}));
  // The checker itself refuses broken XML.
  EXPECT_THROW(ParseXml("<a><b></a></b>"), std::runtime_error);
  EXPECT_THROW(ParseXml("<a>x &nbsp; y</a>"), std::runtime_error);
  EXPECT_THROW(ParseXml("<a></a><b></b>"), std::runtime_error);
}

// A quantity the maps do not show (a joint's gap the depth maps bridge) is not measured in
// every file: null in the JSON (and NaN again when read), an empty value in the CSV, no
// Quantifizierung in the ISYBAU file — never a 0 a reader would take for a closed gap.
TEST_F(InspectionIoTest, AnUnmeasuredQuantityIsLeftEmptyNotZero) {
  auto observations = SampleObservations();
  observations[0].quantities[1].value = std::numeric_limits<double>::quiet_NaN();
  WriteObservationsJson(files_.observations_json, observations);
  const auto json = nlohmann::json::parse(ReadTextFile(files_.observations_json));
  EXPECT_TRUE(json["observations"][0]["quantities"][1]["value"].is_null());
  const auto back = ReadObservationsJson(files_.observations_json);
  ASSERT_NE(back[0].Find("gap_mm"), nullptr);
  EXPECT_FALSE(back[0].Find("gap_mm")->Measured());
  EXPECT_TRUE(back[0].Find("offset_mm")->Measured());

  WriteObservationsCsv(files_.observations_csv, observations);
  EXPECT_NE(ReadTextFile(files_.observations_csv).find(",offset_mm,6.100,mm,gap_mm,,mm,"),
            std::string::npos);

  WriteObservationsIsybau(files_.observations_xml, observations, IsybauHeader{});
  const auto leaves = ParseXml(ReadTextFile(files_.observations_xml));
  const std::string z =
      "Identifikation/Datenkollektive/Zustandsdatenkollektiv/InspizierteAbwassertechnischeAnlage/"
      "OptischeInspektion/Rohrleitung/Inspektionsdaten/RZustand/";
  EXPECT_EQ(leaves.count(z + "Quantifizierung1Numerisch"), 3u);
  EXPECT_EQ(leaves.count(z + "Quantifizierung2Numerisch"), 0u);
}

}  // namespace
}  // namespace sewer3d
