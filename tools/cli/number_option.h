// The one rule for every numeric option of every command (issue 29): the text the user typed is
// parsed whole, once, when the command line is read; NaN, infinities, numbers beyond the type
// and values outside the option's range are refused (exit 2) with the value quoted as typed.
// Nothing is capped, and no value stands for "the default": an option left out keeps its
// default, an option given is used as given or refused.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

namespace metrosync::cli {

// --jobs: worker threads at most (more than any machine metrosync runs on has cores; the pool
// never starts more than there is work, sim/parallel/worker_pool.h).
constexpr int kMaxJobs = 4096;

// The range of a real-valued option: min <= v <= max, or min < v with `above_min`.
struct NumberRange {
  double min = -HUGE_VAL;
  double max = HUGE_VAL;
  bool above_min = false;
};
constexpr NumberRange kAnyFinite{};
constexpr NumberRange kPositive{0.0, HUGE_VAL, true};
constexpr NumberRange kNonNegative{0.0, HUGE_VAL, false};

// The value of `text` for `option`; throws CLI::ValidationError ("--step 0: must be > 0").
double parseNumberText(const std::string& option, const std::string& text, NumberRange range);
long long parseIntegerText(const std::string& option, const std::string& text, long long min,
                           long long max);
std::uint64_t parseUnsignedText(const std::string& option, const std::string& text);

// Options parsed by that rule (`name` as CLI11 takes it: "--step", "--max-output", "INDEX").
CLI::Option* addNumber(CLI::App* app, const std::string& name, double& target, NumberRange range,
                       const std::string& help);
CLI::Option* addNumber(CLI::App* app, const std::string& name, std::optional<double>& target,
                       NumberRange range, const std::string& help);
CLI::Option* addInteger(CLI::App* app, const std::string& name, int& target, long long min,
                        long long max, const std::string& help);
CLI::Option* addInteger(CLI::App* app, const std::string& name, long& target, long long min,
                        long long max, const std::string& help);
// A seed: any integer from 0 to 2^64 - 1.
CLI::Option* addSeed(CLI::App* app, const std::string& name, std::uint64_t& target,
                     const std::string& help);

}  // namespace metrosync::cli
