// observations.csv and the ISYBAU-style observations.xml (io/inspection_io.hpp).

#include <fmt/format.h>

#include <cmath>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/inspection_io.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

/// A CSV field: quoted (quotes doubled) when it holds a comma, quote or line break.
std::string CsvText(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string QuantityColumns(const Observation& o, size_t i) {
  if (i >= o.quantities.size()) return ",,";
  const Quantity& q = o.quantities[i];
  const std::string value = q.Measured() ? fmt::format("{:.3f}", q.value) : std::string();
  return fmt::format("{},{},{}", CsvText(q.name), value, CsvText(q.unit));
}

/// An element on its own line at `depth` (two spaces per level).
void Element(std::string& xml, int depth, const char* name, const std::string& value) {
  xml += fmt::format("{:{}}<{}>{}</{}>\n", "", 2 * depth, name, EscapeMarkup(value), name);
}

/// EN 13508-2 clock reference: the whole hour 1 … 12, two digits as in ISYBAU files.
std::string ClockHour(double clock_h) {
  int hour = static_cast<int>(std::lround(clock_h)) % 12;
  return fmt::format("{:02d}", hour == 0 ? 12 : hour);
}

/// One RZustand: `continuous` "" (a point), "A" (start) or "B" (end) with its running number.
void Condition(std::string& xml, const Observation& o, double station_mm,
               const std::string& continuous, int number) {
  constexpr int d = 8;
  xml += fmt::format("{:{}}<RZustand>\n", "", 2 * (d - 1));
  Element(xml, d, "Station", fmt::format("{:.2f}", station_mm / 1000.0));
  Element(xml, d, "InspektionsKode", o.code);
  if (!o.characterisation.empty()) Element(xml, d, "Charakterisierung1", o.characterisation);
  Element(xml, d, "Verbindung", o.at_joint ? "1" : "0");
  const char* quantification[] = {"Quantifizierung1Numerisch", "Quantifizierung2Numerisch"};
  for (size_t i = 0; i < 2 && i < o.quantities.size(); ++i) {
    if (o.quantities[i].Measured())
      Element(xml, d, quantification[i], fmt::format("{:.2f}", o.quantities[i].value));
  }
  if (!continuous.empty()) {
    Element(xml, d, "Streckenschaden", continuous);
    Element(xml, d, "StreckenschadenLfdNr", std::to_string(number));
  }
  const std::string from = ClockHour(o.clock_from_h), to = ClockHour(o.clock_to_h);
  Element(xml, d, "PositionVon", from);
  if (to != from) Element(xml, d, "PositionBis", to);
  if (!o.remark.empty()) Element(xml, d, "Kommentar", o.remark);
  xml += fmt::format("{:{}}</RZustand>\n", "", 2 * (d - 1));
}

}  // namespace

void WriteObservationsCsv(const std::filesystem::path& path,
                          const std::vector<Observation>& observations) {
  std::string text =
      "id,code,characterisation,station_m,length_m,clock_h,clock_from_h,clock_to_h,at_joint,"
      "confidence,q1_name,q1_value,q1_unit,q2_name,q2_value,q2_unit,remark\n";
  for (const Observation& o : observations) {
    text += fmt::format("{},{},{},{:.2f},{:.3f},{:.2f},{:.2f},{:.2f},{},{:.2f},{},{},{}\n",
                        CsvText(o.id), CsvText(o.code), CsvText(o.characterisation),
                        o.station_mm / 1000.0, o.length_mm / 1000.0, o.clock_h, o.clock_from_h,
                        o.clock_to_h, o.at_joint ? 1 : 0, o.confidence, QuantityColumns(o, 0),
                        QuantityColumns(o, 1), CsvText(o.remark));
  }
  WriteTextFileAtomically(path, text);
}

void WriteObservationsIsybau(const std::filesystem::path& path,
                             const std::vector<Observation>& observations,
                             const IsybauHeader& header) {
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml += "<Identifikation xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\">\n";
  Element(xml, 1, "Version", "2017-07");
  xml += "  <Datenkollektive>\n";
  if (!header.creation_date.empty()) Element(xml, 2, "Erstellungsdatum", header.creation_date);
  Element(xml, 2, "Kommentar", "EN 13508-2 observations measured by sewer3d on the pipe model");
  xml += "    <Kennungen>\n      <Kollektiv>\n";
  Element(xml, 4, "Kennung", "ZUS01");
  Element(xml, 4, "Kollektivart", "2");
  xml += "      </Kollektiv>\n    </Kennungen>\n    <Zustandsdatenkollektiv>\n";
  Element(xml, 3, "Kennung", "ZUS01");
  Element(xml, 3, "Beschreibung", "Zustandsdaten");
  xml += "      <InspizierteAbwassertechnischeAnlage>\n";
  Element(xml, 4, "Objektbezeichnung", header.object_name);
  Element(xml, 4, "Anlagentyp", "1");
  xml += "        <OptischeInspektion>\n";
  if (!header.inspection_date.empty()) Element(xml, 5, "Inspektionsdatum", header.inspection_date);
  xml += "          <Rohrleitung>\n";
  if (header.profile_height_mm > 0.0 || header.profile_width_mm > 0.0) {
    xml += "            <RGrunddaten>\n";
    if (header.profile_height_mm > 0.0)
      Element(xml, 7, "Profilhoehe", fmt::format("{:.0f}", header.profile_height_mm));
    if (header.profile_width_mm > 0.0)
      Element(xml, 7, "Profilbreite", fmt::format("{:.0f}", header.profile_width_mm));
    xml += "            </RGrunddaten>\n";
  }
  xml += "            <Inspektionsdaten>\n";
  int continuous = 0;
  for (const Observation& o : observations) {
    if (IsContinuous(o)) {
      ++continuous;
      Condition(xml, o, o.station_mm, "A", continuous);
      Condition(xml, o, o.station_mm + o.length_mm, "B", continuous);
    } else {
      Condition(xml, o, o.station_mm, "", 0);
    }
  }
  xml +=
      "            </Inspektionsdaten>\n          </Rohrleitung>\n        </OptischeInspektion>\n";
  xml += "      </InspizierteAbwassertechnischeAnlage>\n    </Zustandsdatenkollektiv>\n";
  xml += "  </Datenkollektive>\n</Identifikation>\n";
  WriteTextFileAtomically(path, xml);
}

}  // namespace sewer3d
