// Issue 36's table (tools/bench/speed_figures.h) from the CSVs of one run of speed.sh: each
// figure's measured value, its verdict against the target and by how much it is missed; a part
// not measured says so. Also the cost per step and per event (tools/bench/event_cost_table.h).
// Synthetic CSVs, no simulation, no timing.
#include <gtest/gtest.h>

#include <string>

#include "tools/bench/event_cost_table.h"
#include "tools/bench/speed_figures.h"

namespace mb = metrosync::bench;

namespace {

const mb::SpeedFigure& find(const std::vector<mb::SpeedFigure>& f, const std::string& what) {
  for (const mb::SpeedFigure& g : f)
    if (g.what.find(what) != std::string::npos) return g;
  static const mb::SpeedFigure none{"(none)", "", "", "", ""};
  ADD_FAILURE() << "no figure '" << what << "'";
  return none;
}

mb::SpeedInputs inputs() {
  mb::SpeedInputs in;
  in.ratios_csv =
      "measure,clock,scene,n,error,time_metrosync_s,time_peer_s,ratio,below_target,reason,side\n"
      "final-state,wall,peer-n2,2,1e-05,1,0.5,0.5,1,,run\n"
      "final-state,wall,peer-n2,2,1e-06,1,0.8,0.8,1,,run\n"
      "final-state,wall,peer-n8,8,1e-05,1,2.5,2.5,0,,run\n"
      "final-state,wall,peer-n8,8,1e-06,1,3,3,0,,run\n"
      "final-state,wall,suppression,2,1e-05,1,2.5,2.5,0,,run\n"
      "final-state,wall,suppression,2,1e-06,,,,,the peer does not reach it,run\n"
      "final-state,CPU,peer-n2,2,1e-05,1,2.5,2.5,0,,engine\n"
      "final-state,CPU,peer-n8,8,1e-05,1,1.25,1.25,1,,engine\n"
      "final-state,CPU,n32,32,1e-05,,,,,\"the peer was not run: N = 32\",engine\n";
  in.runpoints_csv =
      "scene,method,wall_seconds,engine_seconds,wall_over_engine,engine_alone_s,wall_over_alone,"
      "target\n"
      "peer-n2,run:verner76:1e-06,0.004,0.003,1.1,0.0025,1.6,1.15\n"
      "peer-n8,run:verner76:1e-06,0.01,0.009,1.05,0.009,1.11,1.15\n";
  in.run_csv =
      "scene,variant,runs,wall_seconds,engine_seconds,ratio,process_wall_s,process_cpu_s,"
      "load1_min,load1_max,target,inconsistent_splits,ratio_min,ratio_max,engine,engine_alone_s,"
      "wall_over_alone,failure\n"
      "yaml/rigs/bench/peer-n2.yaml,,11,0.004,0.003,1.3,0.01,0.009,1,2,1.15,0,1.2,1.4,d,0.0035,"
      "1.14,\n"
      "yaml/rigs/bench/n8.yaml,,11,0.1,0.09,1.1,0.2,0.1,1,2,1.15,0,1,1.2,d,0.08,1.25,\n"
      "yaml/rigs/bench/n8.yaml,simulation.sample=100,11,0.1,0.09,9,0.2,0.1,1,2,1.15,0,1,1.2,d,"
      "0.01,10,\n"
      "default,,11,0.036,0.015,2.4,0.05,0.04,1,2,1.15,0,1.8,2.7,d,0.016,2.25,\n";
  in.process_csv =
      "scene,runs,total_ms,wall_seconds_ms,budget_ms,cpu_ms,unaccounted_ms,load1_min,load1_max\n"
      "peer-n2,21,7.1,2.2,6.3,5,0,0.1,0.2\n";
  in.fit_csv =
      "record,wall_s,cpu_s,model_runs,recovered,run_wall_seconds,fit_over_run,load1_min,"
      "load1_max,failure\n"
      "1,0.9,1.7,300,1,0.01,90,0.1,0.2,\n"
      "2,1.5,2.9,400,1,0.01,150,0.1,0.2,\n"
      "3,2.5,4.8,500,0,0.01,250,0.1,0.2,\n";
  in.continuation_csv =
      "rig,runs,wall_s,cpu_s,points,timed_out,target_s,load1_min,load1_max,failure\n"
      "yaml/rigs/bench/n32.yaml,1,12,20,300,0,20,0.1,0.2,\n"
      "yaml/rigs/n32.yaml,1,60,100,0,1,20,0.1,0.2,stopped after 60 s\n";
  in.eventcost_csv =
      "scene,n,integrator,accuracy,runs,steps,rhs_evals,events,cpu_s,rhs_s,evals_per_step,"
      "evals_per_event,s_per_step,s_per_event,step_in_rhs,event_in_rhs,rhs_share,load1_min,"
      "load1_max,failure\n"
      "experiment-short,2,verner76,1e-06,3,574,7329,248,0.0007,2e-8,12.8,29.6,1.2e-6,2.8e-6,55,"
      "128,0.23,1,2,\n";
  return in;
}

}  // namespace

TEST(SpeedFigures, EachFigureBesideItsTargetAndByHowMuchItIsMissed) {
  const std::vector<mb::SpeedFigure> f = mb::speedFigures(inputs());
  const mb::SpeedFigure& n2 = find(f, "`run` vs the peer, N = 2");
  EXPECT_EQ(n2.verdict, "NOT met");
  EXPECT_EQ(n2.measured, "0.50-0.80x (2 of 2 cells, errors 1e-05 to 1e-06)");
  EXPECT_EQ(n2.by, "worst 0.50x (peer-n2 at 1e-05): 4.00x short; below the target in 2 of 2 cells");
  EXPECT_EQ(find(f, "`run` vs the peer, N = 8").verdict, "met");
  const mb::SpeedFigure& sup = find(f, "suppression");  // met where measured, one cell empty
  EXPECT_EQ(sup.verdict, "NOT met");
  EXPECT_EQ(sup.by, "1 cell not measured on both sides");
  // the engine alone: the peer's scenes only (n32 left out)
  const mb::SpeedFigure& cpu = find(f, "engine alone vs the peer, every scene the peer runs (CPU");
  EXPECT_EQ(cpu.measured, "1.25-2.50x (2 of 2 cells, errors 1e-05 to 1e-05)");
  EXPECT_EQ(find(f, "(wall medians)").verdict, "not measured");
  // `run` against its engine: the worst point, and every bench scene's default sampling only
  EXPECT_EQ(find(f, "`wall_seconds / engine_seconds` on those runs").verdict, "met");
  const mb::SpeedFigure& same = find(f, "recording off, same runs");
  EXPECT_EQ(same.by, "worst 1.60x (peer-n2 run:verner76:1e-06): 1.39x over");
  const mb::SpeedFigure& every = find(f, "every bench scene, default sampling");
  EXPECT_EQ(every.measured, "1.14-1.25x over 2 scenes");
  EXPECT_EQ(every.by, "worst 1.25x (yaml/rigs/bench/n8.yaml): 1.09x over");
  const mb::SpeedFigure& def = find(f, "default rig");
  EXPECT_EQ(def.verdict, "NOT met");
  EXPECT_NE(def.measured.find("2.40x (1.80-2.70x over 11 runs)"), std::string::npos)
      << def.measured;
  EXPECT_NE(def.by.find("2.40x (wall_seconds / engine_seconds): 2.09x over"), std::string::npos);
  const mb::SpeedFigure& proc = find(f, "whole process");
  EXPECT_EQ(proc.measured, "7.1 ms vs wall_seconds 2.2 ms");
  EXPECT_NE(proc.by.find("over by 0.8 ms (1.13x the budget"), std::string::npos) << proc.by;
  const mb::SpeedFigure& fit = find(f, "one fit (fit bench");
  EXPECT_EQ(fit.measured, "median 1.5 s wall, 2.9 s CPU over 3 records");
  EXPECT_EQ(fit.by, "1.50x over");
  EXPECT_EQ(find(f, "against one `run`").by, "1.50x over");
  EXPECT_EQ(find(f, "`yaml/rigs/bench/n32.yaml`").verdict, "met");
  const mb::SpeedFigure& stopped = find(f, "`yaml/rigs/n32.yaml`");
  EXPECT_EQ(stopped.measured, "> 60 s wall (stopped: not finished)");
  EXPECT_EQ(stopped.by, "more than 3.00x over");
  EXPECT_EQ(find(f, "per step and per event").verdict, "reported");
  const std::string md = mb::figuresMarkdown(f);
  EXPECT_NE(md.find("**Issue 36's figures: 3 of 13 targets met.**"), std::string::npos) << md;
}

TEST(SpeedFigures, WhatWasNotMeasuredIsSaid) {
  const std::vector<mb::SpeedFigure> f = mb::speedFigures(mb::SpeedInputs{});
  for (const mb::SpeedFigure& g : f) EXPECT_EQ(g.verdict, "not measured") << g.what;
  EXPECT_NE(mb::figuresMarkdown(f).find("0 of 0 targets met"), std::string::npos);
  mb::SpeedInputs in = inputs();
  in.process_csv = "scene,total_ms\npeer-n2,x\n";  // a malformed CSV names itself
  EXPECT_THROW(mb::speedFigures(in), std::invalid_argument);
}

TEST(EventCost, PerStepAndPerEventAgainstOneRhsEvaluation) {
  mb::EventCostRow r;
  r.steps = 500, r.rhs_evals = 6000, r.events = 250, r.cpu_s = 1e-3, r.rhs_s = 5e-8;
  EXPECT_DOUBLE_EQ(r.evalsPerStep(), 12.0);
  EXPECT_DOUBLE_EQ(r.evalsPerEvent(), 24.0);
  EXPECT_DOUBLE_EQ(r.secondsPerStep(), 2e-6);
  EXPECT_DOUBLE_EQ(r.stepInRhs(), 40.0);  // a step costs 40 evaluations' time, 12 of them RHS
  EXPECT_DOUBLE_EQ(r.eventInRhs(), 80.0);
  EXPECT_DOUBLE_EQ(r.rhsShare(), 0.3);  // 6000 x 50 ns of 1 ms
  r.scene = "s", r.n = 2, r.integrator = "verner76", r.accuracy = 1e-6, r.runs = 3;
  const std::string csv = mb::eventCostCsv({r}, 1, 2);
  EXPECT_NE(csv.find("s,2,verner76,1e-06,3,500,6000,250,0.001,5e-08,12,24,2e-06,4e-06,40,80,0.3,"
                     "1.00,2.00,\n"),
            std::string::npos)
      << csv;
  EXPECT_NE(mb::eventCostMarkdown({r}, "").find("| 40 | 4 us | 80 | 30% |"), std::string::npos)
      << mb::eventCostMarkdown({r}, "");
}
