#include "tools/report/fit_files.h"

#include <cmath>
#include <sstream>

#include "sim/record/atomic_file.h"
#include "tools/report/plot.h"

namespace metrosync {

namespace {

nlohmann::json optionalJson(const std::optional<double>& v) {
  return v ? numberOrNull(*v) : nlohmann::json(nullptr);
}

bool isLength(const std::string& quantity) {
  return quantity == "x";
}

// one block per quantity: t, data, model, residual (x in mm)
std::string plotData(const FitSetup& s, const FitResult& r) {
  std::ostringstream os;
  os.precision(10);
  for (std::size_t q = 0; q < s.quantity_names.size(); ++q) {
    const double unit = isLength(s.quantity_names[q]) ? 1e3 : 1.0;
    os << "# " << s.quantity_names[q] << "\n";
    for (std::size_t i = 0; i < s.observations.size(); ++i) {
      const Observation& o = s.observations[i];
      if (o.quantity != static_cast<int>(q)) continue;
      os << o.t_s << ' ' << unit * o.value << ' ' << unit * r.predicted[i] << ' '
         << unit * (r.predicted[i] - o.value) << '\n';
    }
    os << "\n\n";
  }
  return os.str();
}

std::string plotScript(const FitSetup& s, const std::string& data, const std::string& png,
                       const std::string& title) {
  bool any_length = false;
  for (const std::string& q : s.quantity_names) any_length = any_length || isLength(q);
  std::ostringstream os;
  os << "set terminal pngcairo size 1100,800 noenhanced\n"
     << "set output " << gnuplotQuote(png) << "\n"
     << "set multiplot layout 2,1 title " << gnuplotQuote(title) << "\n"
     << "set xlabel 't (s)'\nset grid\nset key outside right\n"
     << "set ylabel 'angle (rad)'\n";
  if (any_length) os << "set y2label 'x (mm)'\nset y2tics\nset ytics nomirror\n";
  auto panel = [&](bool residuals) {
    os << "plot ";
    for (std::size_t q = 0; q < s.quantity_names.size(); ++q) {
      const std::string& name = s.quantity_names[q];
      const std::string axes = isLength(name) ? " axes x1y2" : " axes x1y1";
      if (q) os << ", ";
      if (residuals) {
        os << gnuplotQuote(data) << " index " << q << " using 1:4" << axes
           << " with points pt 7 ps 0.3"
           << " lc " << q + 1 << " title " << gnuplotQuote(name + " model - data");
      } else {
        os << gnuplotQuote(data) << " index " << q << " using 1:2" << axes
           << " with points pt 7 ps 0.3"
           << " lc " << q + 1 << " title " << gnuplotQuote(name + " data") << ", "
           << gnuplotQuote(data) << " index " << q << " using 1:3" << axes
           << " with lines lw 1.2 lc " << q + 1 << " title "
           << gnuplotQuote(name + " fitted model");
      }
    }
    os << "\n";
  };
  panel(false);
  if (any_length) os << "set y2label 'x residual (mm)'\n";
  os << "set ylabel 'residual (rad)'\n";
  panel(true);
  os << "unset multiplot\n";
  return os.str();
}

}  // namespace

nlohmann::json numberOrNull(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

nlohmann::json fitJson(const FitSetup& s, const FitResult& r, const FitContext& ctx) {
  nlohmann::json values = nlohmann::json::object(), errors = nlohmann::json::object(),
                 ident = nlohmann::json::object(), starts = nlohmann::json::object(),
                 start_from = nlohmann::json::object(), rms_by = nlohmann::json::object();
  nlohmann::json corr = nlohmann::json::array(), keys = nlohmann::json::array();
  for (std::size_t j = 0; j < s.free.size(); ++j) {
    const std::string& key = s.free[j].key;
    keys.push_back(key);
    values[key] = optionalJson(r.values[j]);
    errors[key] = optionalJson(r.std_errors[j]);
    ident[key] = static_cast<bool>(r.identifiable[j]);
    starts[key] = numberOrNull(ctx.starts.at(j));
    start_from[key] = ctx.start_from.at(j);
    nlohmann::json row = nlohmann::json::array();
    for (const auto& c : r.correlation[j]) row.push_back(optionalJson(c));
    corr.push_back(row);
  }
  for (std::size_t q = 0; q < s.quantity_names.size(); ++q)
    rms_by[s.quantity_names[q]] = numberOrNull(r.rms_by_quantity.at(q));
  return {{"rig", ctx.rig_path},
          {"data", ctx.data_path},
          {"model", ctx.model},
          {"free", keys},
          {"values", values},
          {"std_errors", errors},
          {"identifiable", ident},
          {"correlation", corr},
          {"rms", numberOrNull(r.rms)},
          {"rms_by_column", rms_by},
          {"observations", s.observations.size()},
          {"evaluations", r.evaluations},
          {"iterations", r.iterations},
          {"converged", r.converged},
          {"solver", r.solver_summary},
          {"start", starts},
          {"start_from", start_from},
          {"version", metrosyncVersion()}};
}

bool plotFit(const OutputDir& dir, const std::string& png_name, const FitSetup& setup,
             const FitResult& result, const std::string& title) {
  return drawPng(dir, png_name, plotData(setup, result),
                 [&](const std::string& data_path, const std::string& png_path) {
                   return plotScript(setup, data_path, png_path, title);
                 });
}

}  // namespace metrosync
