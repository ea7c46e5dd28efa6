#pragma once
// The Worst nodes tab's list: core's worst_nodes() (the nodes with the smallest dt_safe_i and
// gamma_safe_i of SPEC 9, with the cause in words, as `bounds SCENE --worst N` prints them)
// for the session's model at rest, computed again only when the parameters or springs change.
#include <cstdint>

#include "core/analysis/worst_nodes.hpp"
#include "dampbound/run/session.hpp"

namespace dampbound::ui {

class TunerWorst {
 public:
  /// The `count` worst nodes of the session's model (at rest, at its gamma_i and dt);
  /// `topology` changes whenever the springs do (Tuner::topology()).
  const WorstNodes& get(const Session& session, std::uint64_t topology, int count);
  /// How many times get() computed (tests).
  int computations() const { return computations_; }

 private:
  WorstNodes nodes_;
  bool valid_ = false;
  std::uint64_t topology_ = 0;
  int count_ = 0;
  Params key_;
  int computations_ = 0;
};

}  // namespace dampbound::ui
