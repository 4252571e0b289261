// grtrace/core/ray_status.hpp
// How a traced ray ended. Every ray ends with exactly one of these; they are data, never exceptions.
// The names are part of the command-line contract (JSON "status_counts" keys, EXR "status" channel values).
#pragma once

#include "grtrace/core/host_device.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace grtrace {

enum class RayStatus : std::uint8_t {
  escaped = 0,         ///< left through the escape sphere; the asymptotic direction is known
  captured = 1,        ///< reached the horizon guard r <= (1 + eps) r_h
  hit = 2,             ///< reached a scene object (or a user event)
  max_steps = 3,       ///< the step budget ran out
  step_underflow = 4,  ///< the controller asked for a step below the floor
  non_finite = 5,      ///< NaN/Inf that no step shrink could cure, or the constraint g(k,k) blown (the numbers
                       ///< no longer describe a geodesic; TraceSettings::constraint_tolerance)
};

inline constexpr std::size_t kRayStatusCount = 6;

inline constexpr std::array<std::string_view, kRayStatusCount> kRayStatusNames = {
    "escaped", "captured", "hit", "max_steps", "step_underflow", "non_finite"};

constexpr std::string_view to_string(RayStatus s) { return kRayStatusNames[static_cast<std::size_t>(s)]; }

inline std::optional<RayStatus> ray_status_from_string(std::string_view name) {
  for (std::size_t i = 0; i < kRayStatusCount; ++i)
    if (kRayStatusNames[i] == name) return static_cast<RayStatus>(i);
  return std::nullopt;
}

/// True for the statuses that mean the integration itself failed (as opposed to a physical outcome).
constexpr GRTRACE_HD bool is_failure(RayStatus s) {
  return s == RayStatus::max_steps || s == RayStatus::step_underflow || s == RayStatus::non_finite;
}

}  // namespace grtrace
