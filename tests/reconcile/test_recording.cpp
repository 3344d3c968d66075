// Recording parser: accepts the SPEC format (metadata kept, time optional) and rejects every malformed input with
// one line naming file:line, the column, the value and the expectation; a recording, its baseline and a synthetic
// recording's rows must be of one kind.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "reconcile/experiment.hpp"
#include "reconcile/recording.hpp"
#include "reconcile/synth.hpp"

using namespace sw::reconcile;

namespace {

const char* kGood =
    "# strainwave-recording: 1\n"
    "# kind: torsion\n"
    "# torque_Nm: 44.1   (rated)\n"
    "# source: rig 3\n"
    "time_s,torque_Nm,twist_rad\n"
    "0.0,0.0,0.0\n"
    "0.1,1.5,2e-5\n"
    "0.2,3.0,4.1e-5\n";

/// The InputError message for `text`, or "" when it parses.
std::string error_of(const std::string& text) {
  try {
    parse_recording(text, "rec.csv");
  } catch (const sw::InputError& e) {
    return e.what();
  }
  return "";
}

std::string with_rows(const std::string& header, const std::string& rows, const std::string& kind = "torsion") {
  return "# strainwave-recording: 1\n# kind: " + kind + "\n" + header + "\n" + rows;
}

}  // namespace

TEST(RecordingParser, ReadsMetadataColumnsAndRows) {
  const Recording r = parse_recording(kGood, "rec.csv");
  EXPECT_EQ(r.kind, Kind::Torsion);
  ASSERT_EQ(r.rows(), 3u);
  EXPECT_EQ(r.columns, (std::vector<std::string>{"time_s", "torque_Nm", "twist_rad"}));
  EXPECT_DOUBLE_EQ((*r.column("twist_rad"))[2], 4.1e-5);
  EXPECT_EQ(r.lines[0], 6);
  EXPECT_EQ(r.meta("source").value(), "rig 3");
  EXPECT_DOUBLE_EQ(r.meta_number("torque_Nm").value(), 44.1);
}

TEST(RecordingParser, TimeColumnIsOptionalAndBacklashHasNone) {
  EXPECT_EQ(error_of(with_rows("torque_Nm,twist_rad", "0,0\n1,1e-5\n")), "");
  EXPECT_EQ(error_of(with_rows("wg_angle_deg,torque_Nm,backlash_um", "0,0,20\n10,0,21\n", "backlash")), "");
  EXPECT_NE(error_of(with_rows("time_s,wg_angle_deg,torque_Nm,backlash_um", "0,0,0,20\n", "backlash")), "");
}

TEST(RecordingParser, RoundTripsThroughFormat) {
  const Recording r = parse_recording(kGood, "rec.csv");
  const Recording back = parse_recording(format_recording(r), "rec.csv");
  EXPECT_EQ(back.metadata, r.metadata);
  EXPECT_EQ(back.values, r.values);
}

TEST(RecordingParser, RejectsTextInANumberWithTheLine) {
  const std::string msg = error_of(with_rows("time_s,torque_Nm,twist_rad", "0,0,0\n0.1,abc,1e-5\n"));
  EXPECT_EQ(msg, "rec.csv:5: torque_Nm = 'abc'; expected a finite number");
}

TEST(RecordingParser, RejectsNanAndMissingValues) {
  EXPECT_EQ(error_of(with_rows("time_s,torque_Nm,twist_rad", "0,0,0\n0.1,1,nan\n")),
            "rec.csv:5: twist_rad = 'nan'; expected a finite number");
  EXPECT_EQ(error_of(with_rows("time_s,torque_Nm,twist_rad", "0,0,0\n0.1,,1e-5\n")),
            "rec.csv:5: torque_Nm = ''; expected a finite number");
  EXPECT_NE(error_of(with_rows("time_s,torque_Nm,twist_rad", "0,0\n")).find("rec.csv:4: row has 2 values"),
            std::string::npos);
}

TEST(RecordingParser, RejectsUnsortedTimeWithTheLine) {
  const std::string msg = error_of(with_rows("time_s,torque_Nm,twist_rad", "0,0,0\n0.2,1,1e-5\n0.1,2,2e-5\n"));
  EXPECT_EQ(msg.rfind("rec.csv:6: time_s = 0.1; time must increase", 0), 0u) << msg;
}

TEST(RecordingParser, RejectsUnknownAndMissingColumns) {
  const std::string unknown = error_of(with_rows("time_s,torque_Nm,twist_rad,temperature_C", "0,0,0,20\n"));
  EXPECT_EQ(unknown.rfind("rec.csv:3: column = 'temperature_C'; unknown for kind torsion", 0), 0u) << unknown;
  const std::string missing = error_of(with_rows("time_s,torque_Nm", "0,0\n"));
  EXPECT_EQ(missing.rfind("rec.csv:3: header = 'time_s,torque_Nm'; expected the columns", 0), 0u) << missing;
}

TEST(RecordingParser, RejectsMissingOrUnknownKind) {
  EXPECT_EQ(error_of("# strainwave-recording: 1\ntime_s,torque_Nm,twist_rad\n0,0,0\n"),
            "rec.csv:2: kind missing; expected a '# kind: torsion|transmission|backlash|dynamics' line before the "
            "header");
  EXPECT_EQ(error_of("# strainwave-recording: 1\n# kind: vibration\ntime_s,a\n"),
            "rec.csv:2: kind = 'vibration'; expected one of torsion, transmission, backlash, dynamics");
  EXPECT_EQ(error_of("# kind: torsion\ntime_s,torque_Nm,twist_rad\n").rfind("rec.csv:2: strainwave-recording missing", 0),
            0u);
}

TEST(RecordingParser, AcceptsAUtf8ByteOrderMark) {
  // Spreadsheets exporting "CSV UTF-8" start the file with EF BB BF.
  const Recording r = parse_recording(std::string("\xEF\xBB\xBF") + kGood, "rec.csv");
  EXPECT_EQ(r.kind, Kind::Torsion);
  ASSERT_EQ(r.rows(), 3u);
  EXPECT_EQ(r.metadata.front().first, "strainwave-recording");
}

TEST(RecordingParser, RefusesASemicolonSeparatedFileNamingTheSeparator) {
  const std::string msg = error_of(with_rows("time_s;torque_Nm;twist_rad", "0;0;0\n0,1;1,5;2e-5\n"));
  EXPECT_EQ(msg.rfind("rec.csv:3: header = 'time_s;torque_Nm;twist_rad'; the columns are separated by ';'", 0), 0u)
      << msg;
}

TEST(RecordingParser, TooFewSamplesAreRejectedByTheAnalysis) {
  const Recording r = parse_recording(kGood, "rec.csv");
  Baseline b;
  b.prediction = TorsionPrediction{.compliance_rad_per_Nm = 1e-5};
  try {
    make_experiment(r, b);
    FAIL() << "expected InputError";
  } catch (const sw::InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("rec.csv: rows = 3; reconcile needs at least 100 samples", 0), 0u)
        << e.what();
  }
}

TEST(KindMismatch, ARecordingHeldAgainstAnotherKindsBaselineIsRefusedNamingBoth) {
  const Recording r = parse_recording(kGood, "rec.csv");
  Baseline b;
  b.gear = {.teeth_flexspline = 190, .teeth_circular = 192};
  b.prediction = TransmissionPrediction{};
  try {
    make_experiment(r, b);
    FAIL() << "expected InputError";
  } catch (const sw::InputError& e) {
    EXPECT_EQ(std::string(e.what()), "rec.csv: kind = torsion; the baseline is of kind transmission");
  }
}

TEST(KindMismatch, SynthRowsOfAnotherKindThanTheBaselineAreRefused) {
  SynthOptions o;
  o.baseline.prediction = TorsionPrediction{.compliance_rad_per_Nm = 5e-5};
  o.rows = BacklashRows{};
  try {
    synthesize(o);
    FAIL() << "expected InputError";
  } catch (const sw::InputError& e) {
    EXPECT_EQ(std::string(e.what()), "synth: the rows are laid out for kind backlash; the baseline is of kind torsion");
  }
  o.rows = TorsionRows{};
  EXPECT_EQ(synthesize(o).recording.kind, Kind::Torsion);
}
