// grtrace/grtrace.hpp
// Everything of the header-only core in one include (Eigen + GLM only; no OpenMP, OpenEXR or VTK).
// The GoogleTest kit grtrace/testing.hpp is not included (it needs GTest; link grtrace::testing).
// Rendering I/O lives in grtrace/render/ (link grtrace::render); the VTK frontend in grtrace/viz (grtrace::viz).
#pragma once

#include "grtrace/core/ray_status.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/integrate/controlled_integrator.hpp"
#include "grtrace/integrate/dense_output.hpp"
#include "grtrace/integrate/error_norm.hpp"
#include "grtrace/integrate/event_locator.hpp"
#include "grtrace/integrate/runge_kutta_stepper.hpp"
#include "grtrace/integrate/step_controller.hpp"
#include "grtrace/metric/auto_metric.hpp"
#include "grtrace/metric/dual.hpp"
#include "grtrace/metric/examples/eddington_finkelstein.hpp"
#include "grtrace/metric/examples/ellis_wormhole.hpp"
#include "grtrace/metric/examples/minkowski_components.hpp"
#include "grtrace/metric/examples/reissner_nordstrom.hpp"
#include "grtrace/metric/examples/schwarzschild_components.hpp"
#include "grtrace/metric/examples/schwarzschild_de_sitter.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/minkowski.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/initial_data.hpp"
#include "grtrace/tableau/all_tableaux.hpp"
#include "grtrace/tableau/butcher_tableau.hpp"
#include "grtrace/trace/deflection.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/method_dispatch.hpp"
#include "grtrace/trace/symmetric_sky_table.hpp"
