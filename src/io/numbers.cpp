#include "io/numbers.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <system_error>

namespace asperity::io {

std::string format_double(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

std::string format_exact(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return format_double(x);
}

std::string format_scene_number(double x) {
  if (!std::isfinite(x)) throw std::invalid_argument("cannot write a non-finite number to a scene file");
  return format_double(x);
}

std::string format_g17(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string format_printf(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

std::string format_cell(const char* format, double x) { return std::isfinite(x) ? format_printf(format, x) : "–"; }

std::string format_significant(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

std::string format_short(double x) { return format_significant(x, 3); }

std::string format_count(double x) {
  return x == std::floor(x) && std::abs(x) < 1e15 ? format_printf("%.0f", x) : format_short(x);
}

std::string_view trim(std::string_view s) {
  auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

NumberParse parse_double(std::string_view text, double& out) {
  std::string_view s = trim(text);
  if (s.empty()) return NumberParse::empty;
  std::string lower(s);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  {
    std::string_view l = lower;
    if (l.front() == '+' || l.front() == '-') l.remove_prefix(1);
    if (l == "nan" || l == ".nan" || l == "inf" || l == ".inf" || l == "infinity") return NumberParse::not_finite;
  }
  if (s.front() == '+' && s.size() > 1 && s[1] != '-' && s[1] != '+') s.remove_prefix(1);
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v, std::chars_format::general);
  if (r.ec == std::errc::result_out_of_range) return NumberParse::not_finite;
  if (r.ec != std::errc() || r.ptr == s.data()) return NumberParse::not_a_number;
  if (r.ptr != s.data() + s.size()) {
    const char c = *r.ptr;
    const bool word_follows = c == ' ' || c == '\t' || std::isalpha(static_cast<unsigned char>(c)) || c == '%' ||
                              c == '/' || c == '*' || c == '_';
    return word_follows ? NumberParse::has_unit : NumberParse::not_a_number;
  }
  if (!std::isfinite(v)) return NumberParse::not_finite;
  out = v;
  return NumberParse::ok;
}

bool parse_int(std::string_view text, int& out) {
  std::string_view s = trim(text);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  int v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return false;
  out = v;
  return true;
}

std::string quote(std::string_view s) {
  std::string q;
  for (char c : s) {
    if (c == '\n' || c == '\r' || c == '\t')
      c = ' ';
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      c = '?';  // messages stay one clean line
    q += c;
  }
  if (q.size() > 40) q = q.substr(0, 37) + "...";
  return "'" + q + "'";
}

}  // namespace asperity::io
