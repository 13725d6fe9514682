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
std::string plotData(const FitOutcome& r) {
  std::ostringstream os;
  os.precision(10);
  for (std::size_t q = 0; q < r.quantity_names.size(); ++q) {
    const double unit = isLength(r.quantity_names[q]) ? 1e3 : 1.0;
    os << "# " << r.quantity_names[q] << "\n";
    for (std::size_t i = 0; i < r.observations.size(); ++i) {
      const Observation& o = r.observations[i];
      if (o.quantity != static_cast<int>(q)) continue;
      os << o.t_s << ' ' << unit * o.value << ' ' << unit * r.predicted[i] << ' '
         << unit * (r.predicted[i] - o.value) << '\n';
    }
    os << "\n\n";
  }
  return os.str();
}

std::string plotScript(const FitOutcome& s, const std::string& data, const std::string& png,
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

namespace {

nlohmann::json optimaJson(const FitReport& rep) {
  nlohmann::json out = nlohmann::json::array();
  for (const Optimum& o : rep.outcome.optima) {
    nlohmann::json values = nlohmann::json::object(), start = nlohmann::json::object();
    for (std::size_t j = 0; j < rep.free.size(); ++j) {
      values[rep.free[j].name] = numberOrNull(o.values[j]);
      start[rep.free[j].name] = numberOrNull(o.start[j]);
    }
    out.push_back({{"values", values},
                   {"rms", numberOrNull(o.rms)},
                   {"at_noise_level", o.at_noise},
                   {"rise", numberOrNull(o.rise)},
                   {"start", start}});
  }
  return out;
}

nlohmann::json profileJson(const std::optional<Profile>& p) {
  if (!p) return nullptr;
  return {{"at", {numberOrNull(p->lower_at), numberOrNull(p->upper_at)}},
          {"rise", {numberOrNull(p->lower_rise), numberOrNull(p->upper_rise)}}};
}

// fit.json's per-key objects and the correlation matrix, in --free order
nlohmann::json perKeyJson(const FitReport& rep) {
  const FitOutcome& r = rep.outcome;
  nlohmann::json j = {{"values", nlohmann::json::object()},
                      {"std_errors", nlohmann::json::object()},
                      {"curvature_std_errors", nlohmann::json::object()},
                      {"std_error_from", nlohmann::json::object()},
                      {"intervals", nlohmann::json::object()},
                      {"identifiable", nlohmann::json::object()},
                      {"not_identifiable_because", nlohmann::json::object()},
                      {"profile", nlohmann::json::object()},
                      {"start", nlohmann::json::object()},
                      {"start_from", nlohmann::json::object()},
                      {"keys", nlohmann::json::object()},
                      {"free", nlohmann::json::array()},
                      {"correlation", nlohmann::json::array()}};
  for (std::size_t k = 0; k < rep.free.size(); ++k) {
    const std::string& name = rep.free[k].name;
    j["free"].push_back(name);
    j["keys"][name] = rep.free[k].keys;
    j["values"][name] = optionalJson(r.values[k]);
    j["std_errors"][name] = optionalJson(r.std_errors[k]);
    j["curvature_std_errors"][name] =
        optionalJson(r.curvature_std_errors.empty() ? std::nullopt : r.curvature_std_errors[k]);
    const bool known = !r.std_error_from.empty() && !r.std_error_from[k].empty();
    j["std_error_from"][name] = known ? nlohmann::json(r.std_error_from[k]) : nullptr;
    j["intervals"][name] = nullptr;
    if (!r.intervals.empty() && r.intervals[k])
      j["intervals"][name] = {numberOrNull(r.intervals[k]->first),
                              numberOrNull(r.intervals[k]->second)};
    j["identifiable"][name] = static_cast<bool>(r.identifiable[k]);
    j["not_identifiable_because"][name] =
        r.identifiable[k] ? nlohmann::json(nullptr) : nlohmann::json(r.not_identifiable_because[k]);
    j["profile"][name] = profileJson(r.profiles.empty() ? std::nullopt : r.profiles[k]);
    j["start"][name] = numberOrNull(rep.free[k].start);
    j["start_from"][name] = rep.start_from.at(k);
    nlohmann::json row = nlohmann::json::array();
    for (const auto& c : r.correlation[k]) row.push_back(optionalJson(c));
    j["correlation"].push_back(row);
  }
  return j;
}

}  // namespace

nlohmann::json fitJson(const FitReport& rep) {
  const FitOutcome& r = rep.outcome;
  nlohmann::json rms_by = nlohmann::json::object(), noise = nlohmann::json::object();
  for (std::size_t q = 0; q < r.quantity_names.size(); ++q) {
    rms_by[r.quantity_names[q]] = numberOrNull(r.rms_by_quantity.at(q));
    noise[r.quantity_names[q]] =
        r.noise_by_quantity.at(q) > 0 ? numberOrNull(r.noise_by_quantity[q]) : nullptr;
  }
  nlohmann::json j = {{"rig", rep.rig_path},
                      {"data", rep.data_path},
                      {"model", rep.model},
                      {"rms", numberOrNull(r.rms)},
                      {"rms_by_column", rms_by},
                      {"noise", noise},
                      {"noise_from", r.noise_from},
                      {"converged", r.converged},
                      {"note", r.note},
                      {"solver_converged", r.solver_converged},
                      {"solver", r.solver_summary},
                      {"singular_values", r.singular_values},
                      {"smooth_until_s", numberOrNull(r.smooth_until_s)},
                      {"optima", optimaJson(rep)},
                      {"strategy", r.strategy},
                      {"observations", r.observations.size()},
                      {"evaluations", r.evaluations},
                      {"jacobians", r.jacobians},
                      {"iterations", r.iterations},
                      {"version", metrosyncVersion()}};
  j.update(perKeyJson(rep));
  return j;
}

bool plotFit(const OutputDir& dir, const std::string& png_name, const FitReport& report,
             const std::string& title) {
  return drawPng(dir, png_name, plotData(report.outcome),
                 [&](const std::string& data_path, const std::string& png_path) {
                   return plotScript(report.outcome, data_path, png_path, title);
                 });
}

}  // namespace metrosync
