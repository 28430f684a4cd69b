//! # From the papers to the code
//!
//! Every equation of the five source papers that splinelab implements, and
//! the item that implements it. Equation numbers are the papers' own (the
//! OCR fixes are in the team's design notes). Papers:
//!
//! - **000** — Kuriyama, Kawai and Omura, *S-splines (sampling splines)*:
//!   cardinal interpolating splines, their coefficients and truncation.
//! - **001** — Maeno, Okada and Toriwaki, *Bernstein inverse mapping*:
//!   deforming Bézier patches through sample points.
//! - **002** — Takayama, lecture notes on curves: Hermite, Bézier, rational
//!   Bézier, Catmull–Rom, B-splines and NURBS, drawing by sampling.
//! - **003** — Honda, Mitamura and Iwai, *local modification by knot
//!   insertion*.
//! - **004** — Miura and Sakiyama, *quaternion-integral (QI) curves*.
//!
//! This module holds no code; it is a map.
//!
//! ## 000 — S-splines
//!
//! | eq | what | item |
//! |---|---|---|
//! | 7, 31 | uniform B-spline `N_{0,m}`, its centred form `β` | [`uniform_bspline`](crate::sspline::bspline_uniform::uniform_bspline), [`uniform_bspline_exact`](crate::sspline::bspline_uniform::uniform_bspline_exact), [`SplineFamily::basis_window`](crate::sspline::SplineFamily::basis_window) |
//! | 8–9 | cardinal spline `S(x) = Σ c_i β(x − i)`, `S(j) = δ_{0j}` | [`coefficients`](crate::sspline::coefficients()) |
//! | 10, 28 | truncation at half-width `n` | [`TruncatedBasis`](crate::sspline::TruncatedBasis), [`TruncationAnalysis`](crate::sspline::TruncationAnalysis) |
//! | 11, 19, 37 | node values `V_j` (even, odd order; Beta2) | [`node_values_exact`](crate::sspline::node_values::node_values_exact) |
//! | 12–13, 17 | `c_i = Σ_r κ_r ξ_r^{|i|}` | [`PoleExpansion`](crate::sspline::euler_frobenius::PoleExpansion) |
//! | 16 | Euler–Frobenius polynomial and its poles | [`polynomial`](crate::sspline::euler_frobenius::polynomial), [`poles`](crate::sspline::euler_frobenius::poles), [`poles_rounded`](crate::sspline::coefficients::poles_rounded) |
//! | 18 | cubic `c_i = √3 (√3 − 2)^{|i|}` | [`cubic_coefficients_closed_form`](crate::sspline::beta2::cubic_coefficients_closed_form) |
//! | 20 | S-spline curve `Q(u) = Σ P_i S(u − i)` | [`SsplineCurve`](crate::curves::sspline_curve::SsplineCurve) |
//! | 21–23 | free, periodic and end-tangent ends | [`EndCondition`](crate::sspline::end_conditions::EndCondition), [`EndRule`](crate::sspline::end_conditions::EndRule) |
//! | 24–25 | tensor-product surfaces, curves of curves | [`SsplineSurface`](crate::curves::sspline_surface::SsplineSurface) |
//! | 26–29 | Beta2 S-spline, `c_i = κ₀ ξ₀^{|i|}` | [`coefficients_closed_form`](crate::sspline::beta2::coefficients_closed_form) |
//! | 36 | Beta2 segments `b_{−2..1}` | [`segments`](crate::sspline::beta2::segments) |
//! | 38 | Beta2 pole `ξ₀` | [`pole_closed_form`](crate::sspline::beta2::pole_closed_form) |
//! | 40 | Beta2 weight `κ₀` | [`kappa_closed_form`](crate::sspline::beta2::kappa_closed_form) |
//! | §3 (local update) | one edited point moves `2n + 1` control points | [`SsplineCurve::move_point`](crate::curves::sspline_curve::SsplineCurve::move_point), [`SsplineSurface::move_point`](crate::curves::sspline_surface::SsplineSurface::move_point) |
//! | (tail bound) | `Σ_{|i|>n} |c_i| ≤ 2 Σ_r |κ_r| |ξ_r|^{n+1}/(1 − |ξ_r|)` | [`PoleExpansion::tail_bound`](crate::sspline::euler_frobenius::PoleExpansion::tail_bound), [`truncation_width`](crate::sspline::truncation_width) |
//! | (full build) | coefficients of sampled data, exact or truncated | [`RecursivePrefilter`](crate::sspline::prefilter::RecursivePrefilter), [`ConvolutionPrefilter`](crate::sspline::prefilter::ConvolutionPrefilter) |
//!
//! ## The N-D engine (scipy.ndimage's prefilter and interpolation)
//!
//! Not from the five papers: the engine that applies seed 000's cardinal
//! spline to arrays, in scipy.ndimage's conventions. Sources: M. Unser,
//! A. Aldroubi and M. Eden, *B-spline signal processing I/II*, IEEE Trans.
//! Signal Process. 41 (1993) (the recursive filter, its poles and the mirror
//! initial values); P. Thévenaz, T. Blu and M. Unser, *Interpolation
//! revisited*, IEEE Trans. Med. Imaging 19 (2000) (the gain and the causal
//! initialisation to a horizon); scipy's `ni_splines.c` (the half-sample
//! and periodic initial values, the `mode` names) and `ni_interpolation.c`
//! (the point folding and the 12-sample padding of `nearest` and
//! `grid-constant`).
//!
//! | formula | what | item |
//! |---|---|---|
//! | `D = Λ Π_r (1 − ξ_r z⁻¹)⁻¹ (1 − ξ_r z)⁻¹ s`, `Λ = Π_r (1 − ξ_r)(1 − 1/ξ_r)/V(1)` | the exact inverse filter, a causal and an anti-causal pass per pole (UAE 1993 eq 2.5; TBU 2000 §IV) | [`RecursivePrefilter`](crate::sspline::prefilter::RecursivePrefilter), [`LineFilter`](crate::ndimage::line_filter::LineFilter) |
//! | `c⁺_0 = Σ_{k<K} ξ^k s̃_k`, `|ξ|^K < 2^{−BITS−8}` | causal initial value over the mode's extension, summed to the pole's horizon (TBU 2000 eq 4) | [`LineFilter::apply`](crate::ndimage::line_filter::LineFilter::apply) |
//! | `c⁻_{ν−1} = ξ/(ξ² − 1)(c⁺_{ν−1} + ξ c⁺_{ν−2})` | anti-causal initial value, whole-sample mirror (UAE 1993 II eq 2.8; scipy `mirror`) | [`LineFilter::apply`](crate::ndimage::line_filter::LineFilter::apply) |
//! | `c⁻_{ν−1} = ξ/(ξ − 1) c⁺_{ν−1}` | anti-causal initial value, half-sample reflect (scipy `reflect`, `grid-mirror`) | [`LineFilter::apply`](crate::ndimage::line_filter::LineFilter::apply) |
//! | `c⁻_{ν−1} = −ξ Σ_j ξ^j c⁺_{(ν−1+j) mod ν}` | anti-causal initial value, periodic (scipy `grid-wrap`) | [`LineFilter::apply`](crate::ndimage::line_filter::LineFilter::apply) |
//! | pad `P = max K + 2`, then mirror | `nearest` and `grid-constant`: the exact spline of the extended signal to `2^{−2·BITS}` (scipy pads 12: `ρ^{24}`) | [`LineFilter::apply_padded`](crate::ndimage::line_filter::LineFilter::apply_padded), [`padded_coefficients`](crate::ndimage::nd_prefilter::padded_coefficients) |
//! | `max|D| ≤ gain · Π_r (2/(1 − |ξ_r|))² · max|s|` per axis | growth bound that refuses data the passes could overflow | [`LineFilter::growth`](crate::ndimage::line_filter::LineFilter::growth), [`LineFilter::check_magnitude`](crate::ndimage::line_filter::LineFilter::check_magnitude) |
//! | `|D_W − D| ≤ Σ_{|j|>W} |c_j| · max|s|` | truncated route and parallel blocks of overlap `W` (seed 000 eq 10 with the tail bound) | [`BlockPrefilter`](crate::ndimage::block_filter::BlockPrefilter), [`certified_width`](crate::sspline::width::certified_width) |
//! | `((A + b)^D − A^D) · max|s|`, `A = 1/|V(−1)|` | the truncated route's bound over `D` axes | [`spline_filter`](crate::ndimage::nd_prefilter::spline_filter) |
//! | `x ↦ x mod 2(ν − 1)` mirrored, `mod 2ν` reflected, `mod ν` | the modes' point folding (scipy `ni_interpolation.c`) | [`Mode::fold_coordinate`](crate::ndimage::mode::Mode::fold_coordinate), [`Mode::fold`](crate::ndimage::mode::Mode::fold) |
//! | `f(x) = Σ_i D_i Π_a β(x_a − i_a)` | tensor-product evaluation, derivatives up to the degree | [`Interpolant`](crate::ndimage::interpolant::Interpolant), [`map_coordinates`](crate::ndimage::interpolant::map_coordinates) |
//!
//! ## 001 — Bernstein inverse mapping
//!
//! | eq | what | item |
//! |---|---|---|
//! | 1 | tensor Bézier patch `R(u, v)` | [`Patch`](crate::surface_deformation::patch::Patch) |
//! | 2 | samples `R̃ = B̃ P̃`, the Bernstein–Vandermonde matrix | [`bernstein_vandermonde`](crate::surface_deformation::vandermonde::bernstein_vandermonde), [`tensor_bernstein_vandermonde`](crate::surface_deformation::vandermonde::tensor_bernstein_vandermonde), [`sample`](crate::surface_deformation::inverse_mapping::sample) |
//! | 2–3 | `B̃ = B_u ⊗ B_v` and its solvers | [`solve_tensor`](crate::surface_deformation::bv_solve::solve_tensor), [`BvBidiagonal`](crate::surface_deformation::bv_solve::BvBidiagonal) |
//! | 3 | inverse mapping `P̃ = B̃⁻¹ R̃` | [`control_points`](crate::surface_deformation::inverse_mapping::control_points) |
//! | 4 | deformation `P̃' = P̃ + B̃⁻¹ F` | [`deform`](crate::surface_deformation::inverse_mapping::deform), [`deform_grid`](crate::surface_deformation::inverse_mapping::deform_grid) |
//! | 5–6 (§2.3) | continuity correction at the joins | [`correct_continuity`](crate::surface_deformation::continuity::correct_continuity), [`join_defects`](crate::surface_deformation::continuity::join_defects) |
//! | (conditioning) | `cond(B̃) = cond(B_u) cond(B_v)` | [`matrix_condition`](crate::matrix_condition) |
//!
//! ## 002 — Curves lecture
//!
//! | topic | item |
//! |---|---|
//! | cubic Hermite, Hermite ↔ Bézier | [`Hermite`](crate::curves::hermite::Hermite) |
//! | Bernstein basis | [`bernstein`](crate::bernstein::basis::bernstein), [`bernstein_basis`](crate::bernstein::basis::bernstein_basis) |
//! | de Casteljau (stable, subdivides) | [`de_casteljau`](crate::bernstein::bezier::de_casteljau), [`Bezier`](crate::bernstein::bezier::Bezier), [`compensated`](crate::bernstein::compensated) |
//! | power form (fast, may be unstable) | [`PowerForm`](crate::bernstein::power_form::PowerForm) |
//! | uniform vs adaptive drawing | [`flatten`](crate::curves::flatten::flatten), [`uniform_polyline`](crate::curves::flatten::uniform_polyline) |
//! | rational Bézier, exact circular arcs | [`RationalBezier`](crate::curves::rational_bezier::RationalBezier) |
//! | Catmull–Rom, uniform / centripetal / chordal | [`CatmullRom`](crate::curves::catmull_rom::CatmullRom) |
//! | B-splines, de Boor | [`BSpline`](crate::bspline::de_boor::BSpline) |
//! | NURBS, the exact circle and cylinder | [`NurbsCurve`](crate::bspline::nurbs::NurbsCurve), [`NurbsSurface`](crate::bspline::nurbs::NurbsSurface) |
//! | bicubic Bézier surfaces | [`Patch`](crate::surface_deformation::patch::Patch) |
//!
//! ## 003 — Knot insertion
//!
//! | eq | what | item |
//! |---|---|---|
//! | 1–2 | B-spline of order `k`, knots stored with the points | [`BSpline`](crate::bspline::de_boor::BSpline), [`KnotVector`](crate::bspline::knots::KnotVector) |
//! | 3–6 | Boehm insertion, `α_j = (u − t_j)/(t_{j+k−1} − t_j)` | [`knot_insertion`](crate::bspline::knot_insertion) |
//! | (inverse transformation) | global refinement vs local insertion | [`knot_insertion`](crate::bspline::knot_insertion) (`refine_midpoints`) |
//!
//! ## 004 — Quaternion-integral curves
//!
//! | eq | what | item |
//! |---|---|---|
//! | 1 | quaternion product and inverse | [`quaternion`](crate::qi::quaternion) |
//! | 2 | `C(t) = P + l ∫ q v_x q⁻¹ dτ` | [`QiSegment`](crate::qi::segment::QiSegment) |
//! | 3–4 | `q = cos β + v̂ sin β`, `v̂ = (0, 0, cos α, sin α)` | [`paper_quaternion`](crate::qi::quaternion::paper_quaternion) |
//! | 8–13 | quadratic Bernstein `α(t)`, `β(t)` | [`QiSegment`](crate::qi::segment::QiSegment) |
//! | 16 | closed-form unit tangent `T(α, β)` | [`tangent`](crate::qi::tangent::tangent) |
//! | 18–22 | the G0/G1/G2 system | [`G2System`](crate::qi::g2_system::G2System) |
//! | (end tangents) | circles through the first and last three points | [`start_tangent`](crate::qi::circle_tangent::start_tangent), [`end_tangent`](crate::qi::circle_tangent::end_tangent) |
//! | (solver) | Newton–Raphson | [`newton`](crate::qi::newton::newton), [`interpolate`](crate::qi::interpolate::interpolate) |
//! | (Figure 2) | curvature compared with a cubic spline | [`ClampedCubicSpline`](crate::qi::cubic_spline::ClampedCubicSpline) |
