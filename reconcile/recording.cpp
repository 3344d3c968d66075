#include "reconcile/recording.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "common/error.hpp"

namespace sw::reconcile {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char ch : line) {
    if (ch == sep) {
      out.push_back(trim(cur));
      cur.clear();
    } else {
      cur.push_back(ch);
    }
  }
  out.push_back(trim(cur));
  return out;
}

std::optional<double> parse_number(const std::string& s) {
  if (s.empty()) return std::nullopt;
  double v = 0.0;
  const char* first = s.data();
  const char* last = s.data() + s.size();
  if (*first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, v);
  if (ec != std::errc() || ptr != last || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::string where(const std::string& path, int line) { return path + ":" + std::to_string(line) + ": "; }

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + v[i];
  return s;
}

/// What the parser has read so far.
struct Parse {
  Recording rec;
  int line_no = 0;
  bool have_version = false;
  std::optional<Kind> kind;
  bool have_header = false;
  int time_col = -1;
  double last_time = 0.0;
  int last_time_line = 0;
};

/// A `# key: value` line before the header (a free comment line without ':' is skipped).
void read_metadata(Parse& p, const std::string& line) {
  const std::string& path = p.rec.path;
  const std::string body = trim(line.substr(1));
  const auto colon = body.find(':');
  if (colon == std::string::npos) return;
  const std::string key = trim(body.substr(0, colon));
  const std::string value = trim(body.substr(colon + 1));
  p.rec.metadata.emplace_back(key, value);
  if (key == "strainwave-recording") {
    if (value != "1")
      throw InputError(where(path, p.line_no) + "strainwave-recording = '" + value + "'; expected format version 1");
    p.have_version = true;
  } else if (key == "kind") {
    p.kind = kind_from_name(value);
    if (!p.kind)
      throw InputError(where(path, p.line_no) + "kind = '" + value +
                       "'; expected one of torsion, transmission, backlash, dynamics");
  }
}

/// The header: after the version and the kind, the kind's columns in order (time_s first where the kind allows it).
void read_header(Parse& p, const std::string& line) {
  const std::string& path = p.rec.path;
  if (!p.have_version)
    throw InputError(where(path, p.line_no) +
                     "strainwave-recording missing; expected a '# strainwave-recording: 1' line before the header");
  if (!p.kind)
    throw InputError(where(path, p.line_no) +
                     "kind missing; expected a '# kind: torsion|transmission|backlash|dynamics' line before the header");
  const Kind kind = *p.kind;
  p.rec.kind = kind;
  // Spreadsheets in locales with a decimal comma export CSV separated by semicolons: name that rather than
  // report one unknown column (a decimal comma in the values would be misread if we accepted the file).
  if (line.find(';') != std::string::npos && line.find(',') == std::string::npos)
    throw InputError(where(path, p.line_no) + "header = '" + line +
                     "'; the columns are separated by ';' (a spreadsheet's export with a decimal comma): "
                     "expected comma-separated columns and '.' as the decimal point");
  std::vector<std::string>& columns = p.rec.columns;
  columns = split(line, ',');
  const std::vector<std::string> expected = kind_columns(kind);
  const bool with_time = kind_has_time(kind) && !columns.empty() && columns[0] == "time_s";
  std::vector<std::string> want = expected;
  if (with_time) want.insert(want.begin(), "time_s");
  const std::string listed = (kind_has_time(kind) ? "[time_s,]" : "") + join(expected);
  for (const auto& name : columns)
    if (std::find(want.begin(), want.end(), name) == want.end())
      throw InputError(where(path, p.line_no) + "column = '" + name + "'; unknown for kind " + kind_name(kind) +
                       ", expected the columns " + listed);
  if (columns != want)
    throw InputError(where(path, p.line_no) + "header = '" + join(columns) + "'; expected the columns " + listed +
                     " in this order");
  if (with_time) p.time_col = 0;
  p.rec.values.assign(columns.size(), {});
  p.have_header = true;
}

/// A row of values: one finite number per column, time increasing.
void read_row(Parse& p, const std::string& line) {
  const std::string& path = p.rec.path;
  Recording& rec = p.rec;
  if (line[0] == '#')
    throw InputError(where(path, p.line_no) + "row = '" + line + "'; metadata lines must come before the header");
  const auto fields = split(line, ',');
  if (fields.size() != rec.columns.size())
    throw InputError(where(path, p.line_no) + "row has " + std::to_string(fields.size()) + " values; expected " +
                     std::to_string(rec.columns.size()) + " (" + join(rec.columns) + ")");
  for (std::size_t c = 0; c < fields.size(); ++c) {
    const auto v = parse_number(fields[c]);
    if (!v)
      throw InputError(where(path, p.line_no) + rec.columns[c] + " = '" + fields[c] + "'; expected a finite number");
    rec.values[c].push_back(*v);
  }
  if (p.time_col >= 0) {
    const double t = rec.values[p.time_col].back();
    if (!rec.lines.empty() && !(t > p.last_time))
      throw InputError(where(path, p.line_no) + "time_s = " + fields[p.time_col] + "; time must increase (line " +
                       std::to_string(p.last_time_line) + " has " + std::to_string(p.last_time) + ")");
    p.last_time = t;
    p.last_time_line = p.line_no;
  }
  rec.lines.push_back(p.line_no);
}

}  // namespace

std::optional<Kind> kind_from_name(const std::string& name) {
  for (Kind k : kKinds)
    if (kind_name(k) == name) return k;
  return std::nullopt;
}

std::string kind_name(Kind kind) {
  switch (kind) {
    case Kind::Torsion: return "torsion";
    case Kind::Transmission: return "transmission";
    case Kind::Backlash: return "backlash";
    case Kind::Dynamics: return "dynamics";
  }
  return "?";
}

std::vector<std::string> kind_columns(Kind kind) {
  switch (kind) {
    case Kind::Torsion: return {"torque_Nm", "twist_rad"};
    case Kind::Transmission: return {"wg_angle_rad", "output_angle_rad"};
    case Kind::Backlash: return {"wg_angle_deg", "torque_Nm", "backlash_um"};
    case Kind::Dynamics: return {"wg_speed_rpm", "output_speed_rpm", "mesh_force_N"};
  }
  return {};
}

bool kind_has_time(Kind kind) { return kind != Kind::Backlash; }

const std::vector<double>* Recording::column(const std::string& name) const {
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c] == name) return &values[c];
  return nullptr;
}

std::optional<std::string> Recording::meta(const std::string& key) const {
  for (const auto& [k, v] : metadata)
    if (k == key) return v;
  return std::nullopt;
}

std::optional<double> Recording::meta_number(const std::string& key) const {
  const auto v = meta(key);
  if (!v) return std::nullopt;
  // Allow a trailing comment or unit after whitespace ("44.1   (rated)").
  const std::string first = split(*v, ' ').front();
  const auto x = parse_number(first);
  if (!x) throw InputError(path + ": metadata " + key + " = '" + *v + "'; expected a number");
  return x;
}

Recording parse_recording(const std::string& text, const std::string& path) {
  Parse p;
  p.rec.path = path;
  // A UTF-8 byte-order mark (spreadsheets write one when exporting CSV as UTF-8) is not part of the first line.
  const bool bom = text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0;
  std::istringstream in(bom ? text.substr(3) : text);
  std::string raw;
  while (std::getline(in, raw)) {
    ++p.line_no;
    const std::string line = trim(raw);
    if (line.empty()) continue;
    if (!p.have_header && line[0] == '#') read_metadata(p, line);
    else if (!p.have_header) read_header(p, line);
    else read_row(p, line);
  }
  if (!p.have_header) {
    if (!p.have_version)
      throw InputError(path + ": strainwave-recording missing; expected a '# strainwave-recording: 1' line");
    if (!p.kind) throw InputError(path + ": kind missing; expected a '# kind: ...' metadata line");
    throw InputError(path + ": header missing; expected a line naming the columns");
  }
  return p.rec;
}

Recording load_recording(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path + ": cannot be read; check the recording path");
  std::stringstream ss;
  ss << f.rdbuf();
  return parse_recording(ss.str(), path);
}

std::string format_recording(const Recording& recording) {
  std::string out;
  for (const auto& [k, v] : recording.metadata) out += "# " + k + ": " + v + "\n";
  out += join(recording.columns) + "\n";
  char buf[64];
  for (std::size_t r = 0; r < recording.rows(); ++r) {
    for (std::size_t c = 0; c < recording.columns.size(); ++c) {
      std::snprintf(buf, sizeof buf, "%.17g", recording.values[c][r]);
      out += (c ? "," : "") + std::string(buf);
    }
    out += "\n";
  }
  return out;
}

}  // namespace sw::reconcile
