#pragma once
// dampbound's public API in one include: <dampbound/dampbound.hpp>.
//
//   monitor.hpp                   the paper's bounds over a simulator that is not dampbound
//                                 (the user's own arrays, read in place): the stable API
//   run/session.hpp               a scene stepped under SPEC 8's protocol, with its verdict
//   analysis/linear_stability.hpp the exact limits of the linearised step (SPEC 7, 10)
//   version.hpp                   the version this header belongs to
//
// Each includes the physics it needs (physics/: model, params, forces, bounds, step). Every
// header here compiles on its own; no header outside include/dampbound/ is installed.
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/monitor.hpp"
#include "dampbound/run/session.hpp"
#include "dampbound/version.hpp"
