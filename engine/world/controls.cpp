#include "world/controls.hpp"

#include <cmath>

#include "core/error.hpp"

namespace dda {

void validate_controls(const Controls& c) {
  // Runs every step: a message is built only when its check fails.
  auto require = [](bool ok, const auto&... what) {
    if (!ok) throw Error(msg("controls: ", what...));
  };
  require(std::isfinite(c.g0) && c.g0 >= 0, "g0 must be positive (or 0 for automatic), got ", c.g0);
  require(std::isfinite(c.g1) && c.g1 >= 0, "g1 must be positive (or 0 for automatic), got ", c.g1);
  require(std::isfinite(c.g2) && c.g2 > 0, "g2 must be positive, got ", c.g2);
  require(std::isfinite(c.gg) && c.gg >= 0 && c.gg <= 1, "gg must lie in [0, 1], got ", c.gg);
  require(std::isfinite(c.shear_ratio) && c.shear_ratio >= 0, "shear ratio must be zero or positive, got ",
          c.shear_ratio);
  require(c.open_close_limit >= 1, "open-close limit must be at least 1, got ", c.open_close_limit);
  require(std::isfinite(c.contact_tolerance) && c.contact_tolerance >= 0,
          "contact tolerance must be zero or positive, got ", c.contact_tolerance);
  require(std::isfinite(c.contact_range) && c.contact_range >= 0,
          "contact range must be zero (automatic) or positive, got ", c.contact_range);
  require(std::isfinite(c.fixed_point_factor) && c.fixed_point_factor > 0, "fixed-point factor must be positive, got ",
          c.fixed_point_factor);
  require(c.gravity.allFinite(), "gravity is not finite");
  require(c.cut_factor > 0 && c.cut_factor < 1, "cut factor must lie in (0, 1), got ", c.cut_factor);
  require(c.max_step_cuts >= 0, "max step cuts must be zero or positive");
  require(std::isfinite(c.cg_tolerance) && c.cg_tolerance > 0, "CG tolerance must be positive, got ", c.cg_tolerance);
  require(c.solver.pcg.patch_hops >= 0, "patch hops must be zero (off) or positive, got ", c.solver.pcg.patch_hops);
  require(std::isfinite(c.cg_open_close_tolerance) && c.cg_open_close_tolerance > 0,
          "open-close CG tolerance must be positive, got ", c.cg_open_close_tolerance);
  require(std::isfinite(c.cg_static_tolerance) && c.cg_static_tolerance > 0,
          "static CG tolerance must be positive, got ", c.cg_static_tolerance);
  require(c.threads >= 0, "threads must be zero (all cores) or positive, got ", c.threads);
}

}  // namespace dda
