// Student's t distribution: its distribution function and quantiles, for the findings' intervals
// over a handful of independent runs (effect_interval.h), where the normal quantile 1.96 would
// claim far more than 3 or 5 runs can carry (the 97.5 % quantile with 2 degrees of freedom is
// 4.30). Written here, from the regularised incomplete beta function, to add no dependency.
#pragma once

namespace dv {

// P(T <= t) for T with `dof` > 0 degrees of freedom.
double student_t_cdf(double t, double dof);

// The t with P(T <= t) = p, for 0 < p < 1 and `dof` > 0; accurate to about 1e-12 relative.
double student_t_quantile(double p, double dof);

}  // namespace dv
