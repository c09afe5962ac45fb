#pragma once
// Floating-point operations of the engine's passes, counted by hand from their loops, for
// the micro-benchmarks' flops_per_particle counters (bench/README.md). Every +, -, *, / and
// sqrt counts 1 (a unary minus, a comparison, min/max and integer work count 0), as written
// in the source, per call: a loop-invariant product the compiler may hoist (the -20 * coef of
// grad_factor) still counts. A pass costs
//     flops_per_particle = per_pair * mean neighbours + per_particle.
// When a loop changes, recount it here: the comment above each constant shows its count.
// The pair loops are the vectorised sums of engine/sph/pair_sums.cpp: the kernel's constants
// are hoisted (-20 coef / h^2 is one constant), the volumes m_j / rho_j are computed once per
// particle (Simulation::summed_volume, one division each), and the lanes computed past the end
// of a list are not counted (they do no useful work).
//
// Counted from engine/sph/pair_sums.cpp, engine/fixes/pbf.cpp, engine/fixes/vorticity.cpp,
// engine/fixes/xsph.cpp, engine/core/simulation.cpp and engine/fixes/box.cpp (add_density).

namespace pbf::bench {

// --- building blocks ---

// for_neighbor_vectors, per pair: dx, dy, dz = x_i - x_j (3 -);
// r2 = dx*dx + dy*dy + dz*dz (3 *, 2 +).                                          3 + 5 = 8
inline constexpr double kPairPrelude = 8;
// KernelVectors::W(r2): sqrt, * inv_h, 1 - q, d2 = d * d, coef * (d2 * d2) (2 *), 4 * q,
// 1 + .., * (..)                                                     1 + 1 + 1 + 1 + 2 + 3 = 9
inline constexpr double kW = 9;
// KernelVectors::grad_factor(r2): sqrt, * inv_h, 1 - .., d * d * d (2), * grad_coef (1)
//                                                                            1 + 1 + 1 + 2 + 1 = 6
inline constexpr double kGradFactor = 6;
// KernelVectors::both(r2): sqrt, * inv_h, 1 - q, d3 = d * d * d (2);
// w = coef * (d3 * d) * (1 + 4 * q) (5); g = grad_coef * d3 (1)
//                                                                    1 + 1 + 1 + 2 + 5 + 1 = 11
inline constexpr double kWAndGradFactor = 11;
// The box fix's add_density (one DensityBoundary), per particle, for a particle farther than
// h from every face: per axis to_lo, to_hi (2 -), to_lo + delta, to_hi + delta (2 +),
// outside *= (1 - f_lo) * (1 - f_hi) (2 -, 2 *).                                  3 * 8 = 24
// Near a face it adds the wall fraction polynomial (about 30 per face near) and the
// gradient; those few particles are not counted.
inline constexpr double kBoxWallPerParticle = 24;

// --- pbf: one constraint iteration (engine/fixes/pbf.cpp, constraint) ---

// Density and lambda pass, per pair: prelude 8; both 11; rho += m_j * w (2);
// g = m_j * inv_rho0 * gw (2); gi[0..2] += g * d (6); sum_sq += g * g * r2 (3)
//                                                              8 + 11 + 2 + 2 + 6 + 3 = 32
inline constexpr double kPbfLambdaPerPair = 32;
// per particle: rho = m_i * W(0) (1 + 10); walls: the box (24) and gi[c] += wall_grad[c] *
// inv_rho0 (6); C = rho * inv_rho0 - 1 (2); lambda = -omega * C / (gi.gi + sum_sq + relax)
// (1 *, 1 /, 3 *, 4 +)                                        11 + 24 + 6 + 2 + 9 = 52
inline constexpr double kPbfLambdaPerParticle = 52;
// Correction pass, per pair, with scorr_k = 0 (the default: the s_corr branch is skipped;
// with scorr_k > 0 and scorr_n = 4 add W 10, * inv_wdq 1, 3 *, * scale 1 = 15):
// prelude 8; g = m_j * inv_rho0 * (lambda_i + lambda_j) * grad_factor (1 +, 3 *, 6);
// d[0..2] += g * d (6)                                                  8 + 10 + 6 = 24
inline constexpr double kPbfCorrectionPerPair = 24;
// per particle: the box's gradient, per component move = lambda_i * inv_rho0 * grad (2),
// d += move (1), push = m_i * move * inv_dt (2): 3 * 5 = 15; then x += dp (3)      15 + 3 = 18
inline constexpr double kPbfCorrectionPerParticle = 18;
// One iteration: both passes.                                      32 + 24 = 56, 52 + 18 = 70
inline constexpr double kPbfIterationPerPair = kPbfLambdaPerPair + kPbfCorrectionPerPair;
inline constexpr double kPbfIterationPerParticle = kPbfLambdaPerParticle + kPbfCorrectionPerParticle;

// --- Simulation::summed_density (engine/core/simulation.cpp), which vorticity and xsph read ---

// per pair: prelude 8 (dx, dy, dz feed r2); W 9; rho += m_j * W (2)            8 + 9 + 2 = 19
inline constexpr double kDensityPerPair = 19;
// per particle: rho = m_i * W(0) + sum (2); the box (24); the volume m_i / rho_i (1)  2 + 24 + 1 = 27
inline constexpr double kDensityPerParticle = 27;

// --- vorticity (engine/sph/velocity_curl.cpp, then engine/fixes/vorticity.cpp) ---

// The curl, per pair: prelude 8; g = V_j * grad_factor (1 *, 6);
// gx, gy, gz = g * d (3); u = v_j - v_i (3); w[c] += g_a * u_b - g_b * u_a (3 x 4 = 12)
//                                                                8 + 7 + 3 + 3 + 12 = 33
inline constexpr double kCurlPerPair = 33;
// per particle: |omega| = sqrt(w.w) (3 *, 2 +, sqrt)                                      6
inline constexpr double kCurlPerParticle = 6;
// The gradient of |omega|, per pair: prelude 8; g = V_j * (|w_j| - |w_i|) * grad_factor
// (1 -, 2 *, 6); eta[0..2] += g * d (6)                                        8 + 9 + 6 = 23
inline constexpr double kEtaPerPair = 23;
// per particle: len = sqrt(eta.eta) (6); the flatness test 1e-12 * (w_i / h + 1e-30) (3);
// s = scale * w_i / len (2); a = s * (eta x omega) (3 x 4 = 12); v += a (3)
//                                                               6 + 3 + 2 + 12 + 3 = 26
inline constexpr double kEtaPerParticle = 26;
// The fix's velocity_post (the density it reads is cached; see kDensity*).
//                                                              33 + 23 = 56, 6 + 26 = 32
inline constexpr double kVorticityPerPair = kCurlPerPair + kEtaPerPair;
inline constexpr double kVorticityPerParticle = kCurlPerParticle + kEtaPerParticle;

// --- xsph (engine/fixes/xsph.cpp) ---

// per pair: prelude 8; w = V_j * W (1 *, 9); d[c] += w * (v_j,c - v_i,c) (3 x 3)
//                                                                         8 + 10 + 9 = 27
inline constexpr double kXsphPerPair = 27;
// per particle: dv = c * d (3); v += dv (3)                                          3 + 3 = 6
inline constexpr double kXsphPerParticle = 6;

// --- neighbour lists (engine/sph/neighbor_grid.cpp, build_lists): an estimate ---

// Each candidate j of the 3 x 3 x 3 cells around i costs a distance test: 3 -, 3 *, 2 +: 8.
// The candidates are not public; with cells h wide they fill (3h)^3 where the neighbours
// fill 4/3 pi h^3, so candidates = 27 / (4/3 pi) = 6.45 neighbours:
//                                                          8 * 27 / (4/3 pi) = 51.6 per neighbour
// (a search with smaller cells or a vector test that computes masked lanes changes this).
inline constexpr double kListsPerNeighbor = 8 * 27 / (4.0 / 3.0 * 3.14159265358979323846);

}  // namespace pbf::bench
