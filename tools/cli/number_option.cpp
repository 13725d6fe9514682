#include "tools/cli/number_option.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cstdio>
#include <limits>

#include "base/number_text.h"
#include "yaml/utf8.h"

namespace metrosync::cli {

namespace {

[[noreturn]] void refuse(const std::string& option, const std::string& text,
                         const std::string& why) {
  // the value as typed, its control characters escaped (it goes to a terminal)
  throw CLI::ValidationError(option + " " + (text.empty() ? "''" : printable(text)) + ": " + why);
}

std::string rangeText(NumberRange r) {
  const bool low = r.min > -HUGE_VAL, high = r.max < HUGE_VAL;
  if (low && high)
    return "a number from " + numberText(r.min, 10) + (r.above_min ? " (excluded)" : "") + " to " +
           numberText(r.max, 10);
  if (low) return std::string("a number ") + (r.above_min ? "> " : ">= ") + numberText(r.min, 10);
  if (high) return "a number <= " + numberText(r.max, 10);
  return "a finite number";
}

// from_chars takes no leading '+': one is allowed and dropped.
std::string_view digits(const std::string& text) {
  std::string_view s(text);
  if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
  return s;
}

template <class Int>
Int parseWhole(const std::string& option, const std::string& text, const std::string& want) {
  const std::string_view s = digits(text);
  Int v{};
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty()) refuse(option, text, want);
  return v;
}

template <class Int>
CLI::Option* addIntegerOf(CLI::App* app, const std::string& name, Int& target, long long min,
                          long long max, const std::string& help) {
  return app
      ->add_option_function<std::string>(
          name,
          [&target, name, min, max](const std::string& text) {
            target = static_cast<Int>(parseIntegerText(name, text, min, max));
          },
          help)
      ->type_name("N");
}

// A real-valued option into `target` (a double, or an optional one).
template <class Target>
CLI::Option* addNumberOf(CLI::App* app, const std::string& name, Target& target, NumberRange range,
                         const std::string& help) {
  return app
      ->add_option_function<std::string>(
          name,
          [&target, name, range](const std::string& text) {
            target = parseNumberText(name, text, range);
          },
          help)
      ->type_name("X");
}

}  // namespace

double parseNumberText(const std::string& option, const std::string& text, NumberRange range) {
  const std::string_view s = digits(text);
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  const std::string want = "must be " + rangeText(range);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty() || !std::isfinite(v))
    refuse(option, text, want);
  if (v < range.min || (range.above_min && v == range.min) || v > range.max)
    refuse(option, text, want);
  return v;
}

long long parseIntegerText(const std::string& option, const std::string& text, long long min,
                           long long max) {
  const std::string want =
      "must be an integer from " + std::to_string(min) + " to " + std::to_string(max);
  const long long v = parseWhole<long long>(option, text, want);
  if (v < min || v > max) refuse(option, text, want);
  return v;
}

std::uint64_t parseUnsignedText(const std::string& option, const std::string& text) {
  return parseWhole<std::uint64_t>(option, text,
                                   "must be an integer from 0 to " +
                                       std::to_string(std::numeric_limits<std::uint64_t>::max()) +
                                       " (2^64 - 1)");
}

CLI::Option* addNumber(CLI::App* app, const std::string& name, double& target, NumberRange range,
                       const std::string& help) {
  return addNumberOf(app, name, target, range, help);
}

CLI::Option* addNumber(CLI::App* app, const std::string& name, std::optional<double>& target,
                       NumberRange range, const std::string& help) {
  return addNumberOf(app, name, target, range, help);
}

CLI::Option* addInteger(CLI::App* app, const std::string& name, int& target, long long min,
                        long long max, const std::string& help) {
  return addIntegerOf(app, name, target, std::max<long long>(min, INT_MIN),
                      std::min<long long>(max, INT_MAX), help);
}

CLI::Option* addInteger(CLI::App* app, const std::string& name, long& target, long long min,
                        long long max, const std::string& help) {
  return addIntegerOf(app, name, target, min, max, help);
}

CLI::Option* addSeed(CLI::App* app, const std::string& name, std::uint64_t& target,
                     const std::string& help) {
  return app
      ->add_option_function<std::string>(
          name,
          [&target, name](const std::string& text) { target = parseUnsignedText(name, text); },
          help)
      ->type_name("N");
}

}  // namespace metrosync::cli
