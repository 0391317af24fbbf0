// The standard normal quantile function Phi^-1(p), 0 < p < 1, to double precision: Wichura's
// algorithm AS 241 (PPND16, Applied Statistics 37, 1988), relative error about 1e-16.
#pragma once

namespace filmgrain::physical {

double standard_normal_quantile(double p);

}  // namespace filmgrain::physical
