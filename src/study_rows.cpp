// The rows of instances.csv and their CSV form; the headers of the study's CSV files.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "study/families.hpp"
#include "study_internal.hpp"

namespace certcyl::cli::detail {
using namespace certcyl::study;

const char* const kRowHeader =
    "family,query,instance,k_ulps,expected,method,base,nt,kind,answer,certified_answer,outcome,gap_lo,gap_hi,ns,t_error_ulps,"
    "contract,contract_answer,received_answer,cause";
const char* const kInputsHeader =
    "instance,family,query,k_ulps,expected,certified_answer,gap_lo,gap_hi,gap_sign_ok,stage,certified_by,gmpfr_bits,input_hex";
const char* const kHuntHeader = "method,query,start_family,evaluations,found,answer,certified_answer,outcome,gap_lo,gap_hi,input_hex";

std::string num(double d) {
  if (std::isnan(d)) return "";
  if (std::isinf(d)) return d > 0 ? "inf" : "-inf";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", d);
  return buf;
}
double parse_num(const std::string& s) {
  if (s.empty()) return std::numeric_limits<double>::quiet_NaN();
  if (s == "inf") return std::numeric_limits<double>::infinity();
  if (s == "-inf") return -std::numeric_limits<double>::infinity();
  return std::strtod(s.c_str(), nullptr);  // not stod: it rejects subnormal values
}

void write_row(std::ostream& os, const Row& r) {
  os << r.family << ',' << r.query << ',' << r.instance << ',' << r.k << ',' << r.expected << ',' << r.method << ',' << r.base
     << ',' << r.nt << ',' << r.kind << ',' << r.answer << ',' << r.certified << ',' << r.outcome << ',' << num(r.gap_lo) << ','
     << num(r.gap_hi) << ',' << num(r.ns) << ',' << num(r.t_error) << ',' << r.contract << ',' << r.contract_answer << ','
     << r.received_answer << ',' << r.cause << '\n';
}

std::string csv_field(const std::string& s) {
  const bool plain = s.find_first_of(",\"\r\n") == std::string::npos && (s.empty() || (s.front() != ' ' && s.back() != ' '));
  if (plain) return s;
  std::string q = "\"";
  for (const char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + '"';
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c != '"') {
        out.back() += c;
      } else if (i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else {
        quoted = false;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

Row parse_row(const std::string& line) {
  const auto f = split_csv(line);
  if (f.size() != 20) throw std::runtime_error("instances.csv: bad row '" + line + "'");
  Row r;
  try {
    r.instance = std::stoull(f[2]), r.k = std::stoll(f[3]);
  } catch (const std::logic_error&) {  // not a number, or out of range
    throw std::runtime_error("instances.csv: bad row '" + line + "'");
  }
  r.family = f[0], r.query = f[1], r.expected = f[4];
  r.method = f[5], r.base = f[6], r.nt = f[7], r.kind = f[8], r.answer = f[9], r.certified = f[10], r.outcome = f[11];
  r.gap_lo = parse_num(f[12]), r.gap_hi = parse_num(f[13]), r.ns = parse_num(f[14]), r.t_error = parse_num(f[15]);
  r.contract = f[16], r.contract_answer = f[17], r.received_answer = f[18], r.cause = f[19];
  return r;
}

std::string x_hex(const std::vector<double>& x) {
  std::string s;
  for (double d : x) {
    if (!s.empty()) s += ' ';
    s += hexfloat(d);
  }
  return s;
}

}  // namespace certcyl::cli::detail
