// grtrace/trace/planar_path_table.hpp
// The paths of all the rays a frame needs, in a static spherically symmetric spacetime, from one table of rays.
//
// Why: a ray from a camera at radius r_c stays in its orbital plane and its path u(psi) = 1 / r there depends on one
// number, its angle delta to the outward radial direction in the static frame (trace/planar_geometry.hpp). So the
// frame needs the two-parameter function u(delta, psi), not one integration per pixel. We integrate the reduced
// planar equation u'' = G(u) (metric/static_spherical.hpp; psi is the independent variable, so there is no
// turning-point trouble and no time coordinate) for a table of delta values with the frame's own compile-time
// tableau and controller, and keep each table ray's path on a uniform grid in psi. A pixel then reads:
//   - its fate and sweep: escaped (u falls to 1 / R_sky) or captured (u reaches 1 / r_guard), the angle swept until
//     then, and for escaped rays the angle swept until u = 0, i.e. the exact direction at infinity;
//   - u and u' at any swept angle psi it needs (e.g. where its plane meets an equatorial disk, psi_k = psi_0 + k pi).
//
// Accuracy: each table ray is integrated to the trace settings' tolerance with steps no longer than max_step, and
// its accepted states (u, u', u'' = G(u)) are interpolated by quintic Hermite polynomials (error ~ h^6 |u^(6)| /
// 46080 per step) onto the grid of spacing grid_step; the grid is read back the same way. Across delta, the six nodes
// around the pixel's angle are combined by quintic Lagrange weights in the coordinate of trace/critical_angle_grid.hpp
// (logarithmic near the critical angle delta_c, where u(delta, psi) - u_photon ~ |delta - delta_c| e^psi).
// Each table ray is integrated past its end (beyond u = 0 for escaped rays, inside the horizon guard for captured
// ones) so that neighbours of a pixel have the values the pixel needs; where one does not, the pixel is told so
// and the caller traces it on its own (PlanarSceneTracer falls back to the general tracer and counts it).
//
// Ends only (keep_paths = false): a frame without objects reads each pixel's fate and sweeps, never its path. Then
// no path is stored or resampled and no ray is continued past its end (or traced again to reach farther): the
// same steps up to the end, so the same ends bit for bit, in about half the time (docs/benchmarks.md). The step
// cap max_step stays: besides the interpolation it bounds the error of rays near delta_c, which grows like
// e^psi while they wind (without it the table takes a quarter of the steps, but a ray 1e-6 rad from delta_c
// ends 3e-5 rad off instead of 2e-9: measured at r_c = 50, rtol 1e-9).
#pragma once

#include "grtrace/core/ray_status.hpp"
#include "grtrace/integrate/batch_stepper.hpp"
#include "grtrace/integrate/controlled_integrator.hpp"
#include "grtrace/metric/static_spherical.hpp"
#include "grtrace/trace/critical_angle_grid.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"  // TraceSettings

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <vector>

namespace grtrace {

/// u, u' = du/dpsi on one interval of a path, from the values and first two derivatives at its ends (quintic
/// Hermite interpolation, exact for polynomials of degree 5). t in [0, 1] is the fraction of the interval h.
struct PathPoint {
  double u, w;  ///< u = 1 / r and w = du/dpsi
};
inline PathPoint quintic_hermite(const std::array<double, 3>& a, const std::array<double, 3>& b, double h, double t) {
  const double t2 = t * t, t3 = t2 * t, t4 = t3 * t, t5 = t4 * t;
  const double h0 = 1.0 - 10.0 * t3 + 15.0 * t4 - 6.0 * t5, h1 = t - 6.0 * t3 + 8.0 * t4 - 3.0 * t5;
  const double h2 = 0.5 * (t2 - 3.0 * t3 + 3.0 * t4 - t5), h4 = -4.0 * t3 + 7.0 * t4 - 3.0 * t5;
  const double h5 = 0.5 * (t3 - 2.0 * t4 + t5);
  const double d0 = -30.0 * t2 + 60.0 * t3 - 30.0 * t4, d1 = 1.0 - 18.0 * t2 + 32.0 * t3 - 15.0 * t4;
  const double d2 = 0.5 * (2.0 * t - 9.0 * t2 + 12.0 * t3 - 5.0 * t4), d4 = -12.0 * t2 + 28.0 * t3 - 15.0 * t4;
  const double d5 = 0.5 * (3.0 * t2 - 8.0 * t3 + 5.0 * t4);
  const double u = h0 * a[0] + h * h1 * a[1] + h * h * h2 * a[2] + (1.0 - h0) * b[0] + h * h4 * b[1] + h * h * h5 * b[2];
  const double w = (d0 * a[0] - d0 * b[0]) / h + d1 * a[1] + h * d2 * a[2] + d4 * b[1] + h * d5 * b[2];
  return {u, w};
}

template <StaticSphericalMetric Metric, ExplicitTableau T, StepController C = PIController>
class PlanarPathTable {
 public:
  /// The grid spacing in psi of every stored path (radians).
  static constexpr double grid_step = 1.0 / 32.0;
  /// The longest integration step in psi: the accepted states are interpolated onto the grid with an error of
  /// ~ max_step^6 |u^(6)| / 46080 (|u^(6)| is of the order of u near the photon sphere), 1e-11 and below.
  static constexpr double max_step = 1.0 / 8.0;

  /// One table ray.
  struct Node {
    double delta = 0.0;
    RayStatus status = RayStatus::max_steps;  ///< escaped, captured, or the failure that ended it
    double sweep_sky = nan;       ///< escaped: psi where u = 1 / R_sky
    double sweep_infinity = nan;  ///< escaped: psi where u = 0 (the exact direction at infinity)
    double sweep_guard = nan;     ///< captured: psi where u = 1 / r_guard
    int steps = 0;                ///< accepted integration steps until the end (sky sphere or guard)
    bool stopped_inside = false;  ///< captured: the continuation stopped deep inside the guard (u = 4 / r_guard)
    std::vector<std::array<double, 3>> path;  ///< (u, u', u'') at psi = j grid_step
    static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  };

  /// What a pixel at angle delta reads from the table.
  struct Lookup {
    RayStatus status;     ///< escaped or captured, or a failure status when a neighbouring table ray failed
    double sweep_end;     ///< psi at the sky sphere (escaped) or the horizon guard (captured)
    double sweep_infinity;
    int steps;            ///< the nearest table ray's accepted steps
    bool side_escaped;
    CriticalAngleGrid::Stencil stencil;
  };

  /// Takes the metric, the camera radius, trace settings (tolerance, sky radius, horizon guard, step budget) for the
  /// table rays, the range of delta the frame needs, the number of table rays on each side of delta_c, and whether
  /// the paths are kept for path_at (false: ends only, see the top of this file; path_at then has nothing).
  /// Assumes (checked) a horizon, guard < camera_r < sky radius.
  PlanarPathTable(Metric metric, double camera_r, TraceSettings settings, double delta_min, double delta_max,
                  int nodes_per_side = 1024, C controller = {}, bool keep_paths = true)
      : metric_(metric), settings_(settings), controller_(controller), camera_r_(camera_r), keep_paths_(keep_paths) {
    const double rh = metric.horizon_radius();
    guard_r_ = (1.0 + settings.horizon_epsilon) * rh;
    sky_r_ = settings.escape_radius;
    u_sky_ = 1.0 / sky_r_;
    u_guard_ = 1.0 / guard_r_;
    if (!(rh > 0.0)) throw std::invalid_argument("PlanarPathTable: the metric has no horizon (use another tracer)");
    if (!(camera_r > guard_r_ && camera_r < sky_r_))
      throw std::invalid_argument("PlanarPathTable: need horizon guard < camera radius < sky radius");
    const double a = std::asin(std::min(
        1.0, critical_impact_parameter(metric) / camera_r * std::sqrt(metric.lapse_squared(camera_r))));
    delta_c_ = camera_r >= photon_sphere_radius(metric) ? std::numbers::pi - a : a;
    // Nodes are kept this far off an exactly radial ray, well inside the angle a between delta_c and the radial
    // (5e-10 rad for a camera at 1e10 M: a fixed 1e-9 rad moved every captured node out to an escaping ray there).
    radial_margin_ = std::min(1e-9, 1e-3 * a);
    delta_min = std::clamp(delta_min, 0.0, std::numbers::pi);
    delta_max = std::clamp(delta_max, 0.0, std::numbers::pi);
    // Each side covers the frame's angles on that side; the gap to delta_c is bounded below so that the logarithm
    // stays finite (rays closer than 1e-14 rad to delta_c are read from the last node).
    constexpr double min_gap = 1e-14;
    if (delta_min < delta_c_)
      escaped_ = place_nodes(+1, std::max(delta_c_ - std::min(delta_max, delta_c_), min_gap), delta_c_ - delta_min,
                             nodes_per_side);
    if (delta_max > delta_c_)
      captured_ = place_nodes(-1, std::max(std::max(delta_min, delta_c_) - delta_c_, min_gap), delta_max - delta_c_,
                              nodes_per_side);
    integrate_nodes();
    if (keep_paths_) reach_neighbours_ends();
    for (const int sign : {+1, -1}) {
      Side& side = sign > 0 ? escaped_ : captured_;
      side.ends.reserve(side.nodes.size());
      for (const Node& n : side.nodes)
        side.ends.push_back({sign > 0 ? n.sweep_sky : n.sweep_guard, n.sweep_infinity, n.steps, n.status});
    }
  }

  double critical_angle() const { return delta_c_; }
  double sky_radius() const { return sky_r_; }
  double guard_radius() const { return guard_r_; }
  double camera_radius() const { return camera_r_; }
  const Metric& metric() const { return metric_; }
  long table_steps() const { return total_steps_; }
  /// False for a table of ends only (see the top of this file).
  bool keeps_paths() const { return keep_paths_; }
  /// Table rays traced a second time to reach farther for their neighbours' pixels (see reach_neighbours_ends()).
  long retraced_rays() const { return retraced_; }
  int table_rays() const { return static_cast<int>(escaped_.nodes.size() + captured_.nodes.size()); }

  /// The fate of the ray leaving the camera at angle delta, interpolated from the table rays around it.
  Lookup at(double delta) const {
    const bool escaped = delta < delta_c_;
    const Side& side = escaped ? escaped_ : captured_;
    if (side.nodes.empty()) throw std::out_of_range("PlanarPathTable: delta outside the tabulated range");
    Lookup l{escaped ? RayStatus::escaped : RayStatus::captured, 0.0, 0.0, 0, escaped,
             side.grid.stencil(std::abs(delta - delta_c_))};
    for (int j = 0; j < l.stencil.count; ++j) {
      const NodeEnd& n = side.ends[static_cast<std::size_t>(l.stencil.first + j)];
      const double w = l.stencil.weight[static_cast<std::size_t>(j)];
      if (n.status != l.status) l.status = n.status;  // a failed table ray poisons its neighbourhood
      l.sweep_end += w * n.sweep_end;
      l.sweep_infinity += w * n.sweep_infinity;
    }
    l.steps = side.ends[static_cast<std::size_t>(l.stencil.nearest)].steps;
    return l;
  }

  /// u and u' at swept angle psi >= 0 on the ray of `lookup`; nothing where a table ray around it has no values
  /// (always nothing for a table of ends only).
  std::optional<PathPoint> path_at(const Lookup& lookup, double psi) const {
    const Side& side = lookup.side_escaped ? escaped_ : captured_;
    const double x = psi / grid_step;
    const auto j = static_cast<std::size_t>(x);
    const double t = x - static_cast<double>(j);
    PathPoint p{0.0, 0.0};
    for (int i = 0; i < lookup.stencil.count; ++i) {
      const Node& n = side.nodes[static_cast<std::size_t>(lookup.stencil.first + i)];
      if (!(psi >= 0.0) || j + 1 >= n.path.size()) return std::nullopt;
      const PathPoint q = quintic_hermite(n.path[j], n.path[j + 1], grid_step, t);
      const double w = lookup.stencil.weight[static_cast<std::size_t>(i)];
      p.u += w * q.u;
      p.w += w * q.w;
    }
    return p;
  }

  /// The table ray nodes of one side (+1 escaped, -1 captured), for tests.
  const std::vector<Node>& nodes(int side) const { return side > 0 ? escaped_.nodes : captured_.nodes; }

  /// One table ray at angle delta (also what tests compare against the general tracer). Its path is continued past
  /// its own end (u = 0 for escaped rays, the horizon guard for captured ones) by one maximal step, and at least
  /// to swept angle `reach` (reach_neighbours_ends() asks for more where a neighbour's pixels need it). A table of
  /// ends only stops at the end and stores no path. The table's own nodes are these, bit for bit (integrate_nodes()
  /// integrates several side by side: trace_nodes_batched).
  Node trace_node(double delta, double reach = 0.0) const {
    thread_local std::vector<Accepted> accepted;  // one buffer per thread, reused from node to node
    NodeRun run = begin_node(delta, reach, accepted);
    Integrator integ(run.settings, controller_);
    integ.start(run.eq, run.y0, settings_.initial_step);
    while (continue_node(run, integ.advance(run.eq), integ)) {
    }
    end_node(run);
    return std::move(run.node);
  }

  /// Table rays integrated side by side in one batch (integrate/batch_stepper.hpp), per thread.
  static constexpr int batch_lanes = 4;

 private:
  using Integrator = ControlledIntegrator<T, C, 2>;
  using Accepted = std::pair<double, std::array<double, 3>>;  ///< psi and (u, u', u'') of an accepted step

  // One table ray in progress: its start, its equation, and what it has found so far. trace_node drives one with
  // the integrator's own steps; trace_nodes_batched drives several with batched trial steps. Both feed every
  // accepted step to continue_node, so both give the same node.
  struct NodeRun {
    Node node;
    PlanarRayEquation<Metric> eq;
    Vector<2> y0;
    IntegratorSettings settings;
    double reach = 0.0;
    double psi_end_continuation = std::numeric_limits<double>::infinity();
    bool ended = false;
    int iterations = 0;
    std::vector<Accepted>* accepted = nullptr;  ///< the accepted states (or the last two, for ends only)
  };

  NodeRun begin_node(double delta, double reach, std::vector<Accepted>& accepted) const {
    NodeRun run;
    run.node.delta = delta;
    run.reach = reach;
    // The ray equation degenerates for an exactly radial ray (b = 0, psi never grows): keep nodes off it.
    const double d = std::clamp(delta, radial_margin_, std::numbers::pi - radial_margin_);
    const double r = camera_r_, a = metric_.lapse_squared(r), bscale = radial_scale_squared(metric_, r);
    const double b = r * std::sin(d) / std::sqrt(a);
    run.eq = PlanarRayEquation<Metric>{&metric_, 1.0 / (b * b)};
    run.settings = settings_.integrator;
    run.settings.h_max = std::min(run.settings.h_max, max_step);
    run.settings.h_min = 1e-15 * std::sin(d);  // psi ranges shrink with b: a near-radial ray sweeps ~sin(delta) in all
    run.y0 = Vector<2>(1.0 / r, -std::cos(d) / (std::sin(d) * r * std::sqrt(bscale)));
    accepted.clear();
    run.accepted = &accepted;
    record(run, 0.0, run.y0, run.eq.curvature(run.y0[0]));
    return run;
  }

  // Keeps (psi, (u, u', u'')); u'' = G(u) is passed in: after an accepted step it is the integrator's own f(y)[1].
  void record(NodeRun& run, double psi, const Vector<2>& y, double curvature) const {
    std::vector<Accepted>& accepted = *run.accepted;
    if (!keep_paths_ && accepted.size() == 2) accepted.erase(accepted.begin());  // ends only: crossing() reads two
    accepted.push_back({psi, {y[0], y[1], curvature}});
  }

  // psi where u crosses `level` inside the last accepted interval, on its quintic Hermite: Newton (the derivative
  // w is at hand) kept inside the bracket [lo, hi] that bisection would keep (a Newton step leaving it is replaced
  // by the midpoint); a few iterations where bisection to 1e-17 took ~57 evaluations.
  static double crossing(const std::vector<Accepted>& accepted, double level) {
    const auto& [p0, s0] = accepted[accepted.size() - 2];
    const auto& [p1, s1] = accepted.back();
    const double h = p1 - p0, sign = s1[0] > s0[0] ? 1.0 : -1.0;
    double lo = 0.0, hi = 1.0, t = 0.5;
    for (int it = 0; it < 100 && hi - lo > 1e-17; ++it) {
      const PathPoint q = quintic_hermite(s0, s1, h, t);
      const double f = sign * (q.u - level);
      (f < 0.0 ? lo : hi) = t;
      if (f == 0.0) break;
      const double newton = t - (q.u - level) / (h * q.w);
      const double next = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
      if (std::abs(next - t) < 1e-16) break;
      t = next;
    }
    return p0 + t * h;
  }

  // Takes the outcome of the integrator's last advance (ok: an accepted step, now its state) and records what it
  // tells about the ray: its end (sky sphere or guard) and sweep to infinity, the path beyond them for neighbours.
  // Returns false when the ray needs no more steps.
  bool continue_node(NodeRun& run, StepOutcome outcome, const Integrator& integ) const {
    Node& node = run.node;
    if (outcome != StepOutcome::ok) {
      if (!run.ended)
        node.status = outcome == StepOutcome::non_finite ? RayStatus::non_finite : RayStatus::step_underflow;
      return false;
    }
    // Where the continuation past the end stops: beyond infinity by a margin in psi (escaped), beyond the guard
    // (captured), or well inside the guard (u blows up at the central singularity).
    constexpr double margin = max_step;
    const double u_sky = u_sky_, u_guard = u_guard_, u_stop_inside = 4.0 * u_guard;
    // The integrator already holds G(u) of the new state (f of it, or the FSAL last stage, which is f of the same
    // bits): no second evaluation per step.
    record(run, integ.lambda(), integ.state(), integ.derivative()[1]);
    const double u = integ.state()[0], psi = integ.lambda();
    if (!run.ended) {
      if (run.iterations + 1 > settings_.max_steps) {
        node.status = RayStatus::max_steps;
        return false;
      }
      if (u <= u_sky && integ.state()[1] < 0.0) {
        node.status = RayStatus::escaped;
        node.sweep_sky = crossing(*run.accepted, u_sky);
        node.steps = integ.accepted();
        run.ended = true;
      } else if (u >= u_guard) {
        node.status = RayStatus::captured;
        node.sweep_guard = crossing(*run.accepted, u_guard);
        node.steps = integ.accepted();
        run.psi_end_continuation = std::max(node.sweep_guard, run.reach) + margin;
        run.ended = true;
      }
    }
    if (run.ended && node.status == RayStatus::escaped && std::isnan(node.sweep_infinity) && u <= 0.0) {
      node.sweep_infinity = crossing(*run.accepted, 0.0);
      run.psi_end_continuation = std::max(node.sweep_infinity, run.reach) + margin;
    }
    if (!keep_paths_ && run.ended && (node.status == RayStatus::captured || !std::isnan(node.sweep_infinity)))
      return false;
    if (psi >= run.psi_end_continuation) return false;
    if (run.ended && node.status == RayStatus::captured && u >= u_stop_inside) {
      node.stopped_inside = true;
      return false;
    }
    return ++run.iterations < settings_.max_steps + 100000;
  }

  void end_node(NodeRun& run) const {
    if (keep_paths_) resample(*run.accepted, run.eq, run.node.path);
  }

  // Table rays nodes[i].delta, i in [begin, end), integrated batch_lanes at a time: each lane one ray, its trial
  // steps taken together by the batched stepper and judged by the ray's own integrator (judge_trial), so each ray
  // takes the steps trace_node takes, bit for bit; a lane whose ray ends takes the next one. Only for controllers
  // on an embedded estimate (integrate_nodes() uses trace_node otherwise).
  void trace_nodes_batched(std::vector<Node>& nodes, int begin, int end) const {
    constexpr int W = batch_lanes;
    using Stepper = RungeKuttaBatchStepper<T, 2, W>;
    struct Lane {
      std::optional<NodeRun> run;
      std::optional<Integrator> integ;
      int index = -1;
      std::vector<Accepted> accepted;
    };
    thread_local std::array<Lane, W> lanes;  // the buffers are reused from call to call
    std::array<PlanarRayEquation<Metric>, W> eqs;
    eqs.fill(PlanarRayEquation<Metric>{&metric_, 1.0});
    int next = begin;
    auto take_next = [&](int l) {
      Lane& lane = lanes[static_cast<std::size_t>(l)];
      lane.run.reset();
      if (next >= end) return;
      lane.index = next++;
      lane.run.emplace(begin_node(nodes[static_cast<std::size_t>(lane.index)].delta, 0.0, lane.accepted));
      lane.integ.emplace(lane.run->settings, controller_);
      lane.integ->start(lane.run->eq, lane.run->y0, settings_.initial_step);
      eqs[static_cast<std::size_t>(l)] = lane.run->eq;
    };
    auto finish = [&](int l) {
      Lane& lane = lanes[static_cast<std::size_t>(l)];
      end_node(*lane.run);
      nodes[static_cast<std::size_t>(lane.index)] = std::move(lane.run->node);
      take_next(l);
    };
    for (int l = 0; l < W; ++l) take_next(l);

    const auto rhs = [&](const Batch<2, W>& y, Batch<2, W>& dy) {
      for (std::size_t l = 0; l < W; ++l) {
        dy[0][l] = y[1][l];
        dy[1][l] = eqs[l].curvature(y[0][l]);
      }
    };
    Stepper stepper;
    Batch<2, W> y{}, f{}, y_new{}, err{};
    typename Stepper::Steps h{};
    for (;;) {
      // Every lane ready for a trial step (a ray whose step underflows ends here), or empty.
      int first_active = -1;
      for (int l = 0; l < W; ++l) {
        Lane& lane = lanes[static_cast<std::size_t>(l)];
        while (lane.run) {
          if (const Optional<double> trial = lane.integ->trial_step()) {
            h[static_cast<std::size_t>(l)] = *trial;
            set_lane(y, l, lane.integ->state());
            set_lane(f, l, lane.integ->derivative());
            if (first_active < 0) first_active = l;
            break;
          }
          continue_node(*lane.run, StepOutcome::step_underflow, *lane.integ);
          finish(l);
        }
      }
      if (first_active < 0) return;
      // Empty lanes compute on an active lane's numbers (their results are not read): no NaN or denormal traffic.
      for (int l = 0; l < W; ++l)
        if (!lanes[static_cast<std::size_t>(l)].run) {
          h[static_cast<std::size_t>(l)] = h[static_cast<std::size_t>(first_active)];
          set_lane(y, l, lane_of(y, first_active));
          set_lane(f, l, lane_of(f, first_active));
          eqs[static_cast<std::size_t>(l)] = eqs[static_cast<std::size_t>(first_active)];
        }
      stepper.step(rhs, y, f, h, y_new, err);
      for (int l = 0; l < W; ++l) {
        Lane& lane = lanes[static_cast<std::size_t>(l)];
        if (!lane.run) continue;
        const bool accepted = lane.integ->judge_trial(lane.run->eq, h[static_cast<std::size_t>(l)], lane_of(y_new, l),
                                                      lane_of(err, l), lane_of(stepper.stage(T::stages - 1), l));
        if (accepted && !continue_node(*lane.run, StepOutcome::ok, *lane.integ)) finish(l);
      }
    }
  }

  // What at() reads of a node, packed (24 bytes, where a Node is 152): a pixel reads CriticalAngleGrid::stencil_size
  // neighbours.
  struct NodeEnd {
    double sweep_end;  ///< sweep_sky (escaped side) or sweep_guard (captured side)
    double sweep_infinity;
    int steps;
    RayStatus status;
  };

  struct Side {
    CriticalAngleGrid grid;
    std::vector<Node> nodes;
    std::vector<NodeEnd> ends;  ///< nodes' ends, in the same order
  };

  // The path on the uniform grid psi = j h, from the accepted states by quintic Hermite interpolation.
  static void resample(const std::vector<Accepted>& accepted,
                       const PlanarRayEquation<Metric>& eq, std::vector<std::array<double, 3>>& path) {
    if (accepted.size() < 2) return;
    const double last = accepted.back().first;
    path.reserve(static_cast<std::size_t>(last / grid_step) + 2);
    std::size_t k = 0;
    for (int j = 0;; ++j) {
      const double psi = j * grid_step;
      if (psi > last) break;
      while (k + 2 < accepted.size() && accepted[k + 1].first < psi) ++k;
      const auto& [p0, s0] = accepted[k];
      const auto& [p1, s1] = accepted[k + 1];
      const double h = p1 - p0;
      const PathPoint q = h > 0.0 ? quintic_hermite(s0, s1, h, std::clamp((psi - p0) / h, 0.0, 1.0))
                                  : PathPoint{s0[0], s0[1]};
      path.push_back({q.u, q.w, eq.curvature(q.u)});
    }
  }

  // The nodes of one side (sign +1: escaped, delta = delta_c - gap; -1: captured, delta = delta_c + gap), their
  // angles set, not yet integrated.
  Side place_nodes(int sign, double gap_min, double gap_max, int nodes) const {
    Side side{CriticalAngleGrid(gap_min, gap_max, nodes), {}, {}};
    side.nodes.resize(static_cast<std::size_t>(side.grid.nodes));
    for (int i = 0; i < side.grid.nodes; ++i)
      side.nodes[static_cast<std::size_t>(i)].delta = delta_c_ - sign * side.grid.gap_of_node(i);
    return side;
  }

  // Integrates every node of both sides in one parallel loop (one wait for the slowest thread, not one per side):
  // chunks of table rays, each integrated batch_lanes at a time (trace_nodes_batched: the same nodes as
  // trace_node, bit for bit, in about a third of the time: docs/benchmarks.md); trace_node itself, ray by ray,
  // for step doubling.
  void integrate_nodes() {
    constexpr int chunk = C::estimate == ErrorEstimate::embedded ? 32 : 8;
    struct Chunk {
      std::vector<Node>* nodes;
      int begin, end;
    };
    std::vector<Chunk> chunks;
    for (Side* side : {&escaped_, &captured_}) {
      const int n = static_cast<int>(side->nodes.size());
      for (int begin = 0; begin < n; begin += chunk)
        chunks.push_back({&side->nodes, begin, std::min(n, begin + chunk)});
    }
    const int count = static_cast<int>(chunks.size());
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1)
#endif
    for (int c = 0; c < count; ++c) {
      const Chunk& k = chunks[static_cast<std::size_t>(c)];
      if constexpr (C::estimate == ErrorEstimate::embedded) {
        trace_nodes_batched(*k.nodes, k.begin, k.end);
      } else {
        for (int i = k.begin; i < k.end; ++i) {
          Node& node = (*k.nodes)[static_cast<std::size_t>(i)];
          node = trace_node(node.delta);
        }
      }
    }
    for (const Side* side : {&escaped_, &captured_})
      for (const Node& node : side->nodes) total_steps_ += node.steps;
  }

  // A pixel reads its stencil's paths up to its own end, interpolated from the stencil's ends (path_at): so each
  // node must reach the farthest end among the nodes that share a stencil with it (stencil_size - 1 on each side).
  // The few nodes that stop short are traced again with that reach (both sides in one parallel loop).
  void reach_neighbours_ends() {
    std::vector<std::pair<Node*, double>> short_nodes;  // the node and the swept angle it must reach
    for (const int sign : {+1, -1}) {
      std::vector<Node>& nodes = (sign > 0 ? escaped_ : captured_).nodes;
      const int n = static_cast<int>(nodes.size());
      for (int i = 0; i < n; ++i) {
        double farthest = 0.0;
        constexpr int sharing = CriticalAngleGrid::stencil_size - 1;  // nodes on each side sharing a stencil
        for (int j = std::max(0, i - sharing); j <= std::min(n - 1, i + sharing); ++j) {
          const Node& o = nodes[static_cast<std::size_t>(j)];
          const double end = sign > 0 ? o.sweep_sky : o.sweep_guard;
          if (std::isfinite(end)) farthest = std::max(farthest, end);
        }
        Node& node = nodes[static_cast<std::size_t>(i)];
        const double covered = static_cast<double>(node.path.size()) * grid_step - 2.0 * grid_step;
        if (node.status != RayStatus::escaped && node.status != RayStatus::captured) continue;
        if (covered >= farthest) continue;
        if (node.status == RayStatus::captured && node.stopped_inside) continue;  // nothing more to read there
        short_nodes.push_back({&node, farthest});
      }
    }
    const int count = static_cast<int>(short_nodes.size());
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 4)
#endif
    for (int i = 0; i < count; ++i) {
      auto& [node, reach] = short_nodes[static_cast<std::size_t>(i)];
      const int node_steps = node->steps;
      *node = trace_node(node->delta, reach);
      node->steps = node_steps;
    }
    retraced_ += count;
  }

  Metric metric_;
  TraceSettings settings_;
  C controller_;
  double camera_r_, guard_r_ = 0.0, sky_r_ = 0.0;
  double u_sky_ = 0.0, u_guard_ = 0.0;  ///< 1 / sky_r_ and 1 / guard_r_: where table rays end
  bool keep_paths_ = true;
  double delta_c_ = 0.0;
  double radial_margin_ = 1e-9;
  Side escaped_, captured_;
  long total_steps_ = 0;
  long retraced_ = 0;
};

}  // namespace grtrace
