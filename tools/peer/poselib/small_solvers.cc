// Runs one of PoseLib's small minimal solvers on the instances small_instances.py writes
// (its PEER file: PoseLib's inputs, x y z each, x y for p35pf's image points) and prints
// the figures tools/emitted_solver/main.rs prints for our emitted solver on the same
// instances (its OURS file): per-call time, solutions per instance, and how many planted
// solutions (our unknowns, the SOLUTIONS file) are recovered to 1e-6 relative, PoseLib's
// poses converted to our unknowns. Our own code, compiled against a PoseLib checkout the
// user provides (small_solvers.sh).
//
//   small_solvers PROBLEM PEER SOLUTIONS
//
// PROBLEM: p3p, gp3p, up2p_elim (PoseLib's up2p), relpose_upright_3pt_elim and
// relpose_upright_3pt_tan (PoseLib's relpose_upright_3pt), p3ll, relpose_6pt_focal
// (PoseLib's relpose_6pt_shared_focal), p2p2pl and p2p2pl_canonical (PoseLib's p2p2pl),
// p35pf and p35pf_nullspace (PoseLib's p35pf). Work per call: PoseLib's poses (rotation and translation; with the focal
// length for relpose_6pt_focal and p35pf); ours returns what its problem file solves for
// (depths for p3p and gp3p; the rotation alone for p3ll; for relpose_6pt_focal the
// fundamental matrix in the null-space basis and the focal length, from that basis as
// data, whose computation PoseLib's time includes and ours does not; for p2p2pl the
// rotation and the scaled depth of point 0; for p35pf those and the positive focal
// length, and PoseLib's time includes scaling the image points, ours does not; for
// p35pf_nullspace the projection matrix's coordinates in the null-space basis of its seven
// linear equations, from that basis as data, which PoseLib computes within its call; for
// p2p2pl_canonical the rotation's (b, c) in the canonical frames, from data moved to them,
// which PoseLib does within its call).
#include <PoseLib/poselib.h>

#include "rows.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace {

using Vec3 = Eigen::Vector3d;
using Points = std::vector<Vec3>;

// The `count` vectors of block `block` of a peer line (blocks of `count` x y z each).
Points block(const std::vector<double> &r, int block, int count) {
    Points out;
    for (int i = 0; i < count; ++i) {
        int k = 3 * (count * block + i);
        out.emplace_back(r[k], r[k + 1], r[k + 2]);
    }
    return out;
}

// The first `count` image points of a peer line (x y each).
std::vector<Eigen::Vector2d> image_points(const std::vector<double> &r, int count) {
    std::vector<Eigen::Vector2d> out;
    for (int i = 0; i < count; ++i) out.emplace_back(r[2 * i], r[2 * i + 1]);
    return out;
}

// (b, c, d) = (x, y, z) / w of a pose's quaternion and 1 + b^2 + c^2 + d^2, the scale of
// our unnormalised rotation Rq.
std::vector<double> quaternion_bcd(const poselib::CameraPose &pose) {
    double w = pose.q(0), b = pose.q(1) / w, c = pose.q(2) / w, d = pose.q(3) / w;
    return {b, c, d, 1.0 + b * b + c * c + d * d};
}

// One problem: the width of a peer line, the call, and a pose's value in our unknowns.
struct Problem {
    size_t width;
    size_t unknowns;
    std::function<void(const std::vector<double> &, std::vector<poselib::CameraPose> *)> solve;
    std::function<std::vector<double>(const std::vector<double> &, const poselib::CameraPose &)> ours;
    // Unknowns whose joint sign is free (a translation of unit length).
    std::vector<int> sign_free;
    // Instead of `solve` and `ours`, for a solver that returns image pairs (a pose and
    // the cameras).
    std::function<void(const std::vector<double> &, poselib::ImagePairVector *)> solve_pairs;
    std::function<std::vector<double>(const std::vector<double> &, const poselib::ImagePair &)> ours_pair;
    // Instead of `solve` and `ours`, for a solver that returns poses and focal lengths.
    std::function<void(const std::vector<double> &, std::vector<poselib::CameraPose> *, std::vector<double> *)>
        solve_focal;
    std::function<std::vector<double>(const std::vector<double> &, const poselib::CameraPose &, double)> ours_focal;
};

Eigen::Matrix3d skew(const Vec3 &t) {
    Eigen::Matrix3d m;
    m << 0, -t(2), t(1), t(2), 0, -t(0), -t(1), t(0), 0;
    return m;
}

// PoseLib's calls shared by two problems each (the same peer line, our unknowns differ).
void upright_3pt(const std::vector<double> &r, std::vector<poselib::CameraPose> *out) {
    poselib::relpose_upright_3pt(block(r, 0, 3), block(r, 1, 3), out);
}

void p2p2pl(const std::vector<double> &r, std::vector<poselib::CameraPose> *out) {
    poselib::p2p2pl(block(r, 0, 2), block(r, 1, 2), block(r, 2, 2), block(r, 3, 2), block(r, 4, 2), out);
}

void p35pf(const std::vector<double> &r, std::vector<poselib::CameraPose> *out, std::vector<double> *focals) {
    Points X;
    for (int i = 0; i < 4; ++i) X.emplace_back(r[8 + 3 * i], r[9 + 3 * i], r[10 + 3 * i]);
    poselib::p35pf(image_points(r, 4), X, out, focals);
}

bool problem(const std::string &name, Problem *p) {
    if (name == "p3p") {
        *p = {18, 3,
              [](const std::vector<double> &r, std::vector<poselib::CameraPose> *out) {
                  poselib::p3p(block(r, 0, 3), block(r, 1, 3), out);
              },
              [](const std::vector<double> &r, const poselib::CameraPose &pose) {
                  // Depth along (x, y, 1): the camera-frame point's z.
                  std::vector<double> d;
                  for (const auto &X : block(r, 1, 3)) d.push_back(pose.apply(X).z());
                  return d;
              },
              {}};
    } else if (name == "gp3p") {
        *p = {27, 3,
              [](const std::vector<double> &r, std::vector<poselib::CameraPose> *out) {
                  poselib::gp3p(block(r, 0, 3), block(r, 1, 3), block(r, 2, 3), out);
              },
              [](const std::vector<double> &r, const poselib::CameraPose &pose) {
                  // Distance along the unit ray from its origin.
                  auto o = block(r, 0, 3), x = block(r, 1, 3), X = block(r, 2, 3);
                  std::vector<double> d;
                  for (int i = 0; i < 3; ++i) d.push_back((pose.apply(X[i]) - o[i]).dot(x[i]));
                  return d;
              },
              {}};
    } else if (name == "up2p_elim") {
        *p = {12, 5,
              [](const std::vector<double> &r, std::vector<poselib::CameraPose> *out) {
                  poselib::up2p(block(r, 0, 2), block(r, 1, 2), out);
              },
              [](const std::vector<double> &, const poselib::CameraPose &pose) {
                  Eigen::Matrix3d R = pose.R();
                  return std::vector<double>{R(0, 0), R(0, 2), pose.t(0), pose.t(1), pose.t(2)};
              },
              {}};
    } else if (name == "relpose_upright_3pt_elim") {
        *p = {18, 5,
              upright_3pt,
              [](const std::vector<double> &, const poselib::CameraPose &pose) {
                  Eigen::Matrix3d R = pose.R();
                  Vec3 t = pose.t.normalized();
                  return std::vector<double>{R(0, 0), R(0, 2), t(0), t(1), t(2)};
              },
              {2, 3, 4}};
    } else if (name == "relpose_upright_3pt_tan") {
        *p = {18, 4,
              upright_3pt,
              [](const std::vector<double> &, const poselib::CameraPose &pose) {
                  // q = tan(a / 2) = sin a / (1 + cos a) of the yaw a.
                  Eigen::Matrix3d R = pose.R();
                  Vec3 t = pose.t.normalized();
                  return std::vector<double>{R(0, 2) / (1.0 + R(0, 0)), t(0), t(1), t(2)};
              },
              {1, 2, 3}};
    } else if (name == "p3ll") {
        *p = {27, 3,
              [](const std::vector<double> &r, std::vector<poselib::CameraPose> *out) {
                  poselib::p3ll(block(r, 0, 3), block(r, 1, 3), block(r, 2, 3), out);
              },
              [](const std::vector<double> &, const poselib::CameraPose &pose) {
                  double w = pose.q(0);
                  return std::vector<double>{pose.q(1) / w, pose.q(2) / w, pose.q(3) / w};
              },
              {}};
    } else if (name == "relpose_6pt_focal") {
        *p = {63, 3, nullptr, nullptr, {},
              [](const std::vector<double> &r, poselib::ImagePairVector *out) {
                  poselib::relpose_6pt_shared_focal(block(r, 0, 6), block(r, 1, 6), out);
              },
              [](const std::vector<double> &r, const poselib::ImagePair &pair) {
                  // F = K^-1 [t]x R K^-1 (K diagonal) in our basis: lambda F - x F1 - y F2 = F3
                  // over the nine entries (row-major, the basis after the 36 point numbers).
                  double f = pair.camera1.focal();
                  Eigen::Matrix3d kinv = Vec3(1 / f, 1 / f, 1).asDiagonal();
                  Eigen::Matrix3d F = kinv * skew(pair.pose.t) * pair.pose.R() * kinv;
                  Eigen::Matrix<double, 9, 3> a;
                  Eigen::Matrix<double, 9, 1> b;
                  for (int k = 0; k < 9; ++k) {
                      a(k, 0) = F(k / 3, k % 3);
                      a(k, 1) = -r[36 + k];
                      a(k, 2) = -r[45 + k];
                      b(k) = r[54 + k];
                  }
                  Vec3 s = a.colPivHouseholderQr().solve(b);
                  return std::vector<double>{s(1), s(2), 1 / (f * f)};
              }};
    } else if (name == "p2p2pl") {
        *p = {30, 4,
              p2p2pl,
              [](const std::vector<double> &r, const poselib::CameraPose &pose) {
                  // l: the depth of point 0 scaled like Rq, (1 + b^2 + c^2 + d^2) z_0.
                  auto s = quaternion_bcd(pose);
                  double depth = pose.apply(block(r, 1, 2)[0]).z();
                  return std::vector<double>{s[0], s[1], s[2], s[3] * depth};
              },
              {}};
    } else if (name == "p2p2pl_canonical") {
        // PoseLib's p2p2pl on the given frames; a line also holds the canonical frames'
        // rotations rc (camera) and r0 (world), row-major, after them: our unknowns are
        // (b, c) of rc R r0', whose quaternion is (1, b, c, -b c).
        *p = {48, 2,
              p2p2pl,
              [](const std::vector<double> &r, const poselib::CameraPose &pose) {
                  Eigen::Matrix3d rc, r0;
                  for (int k = 0; k < 9; ++k) {
                      rc(k / 3, k % 3) = r[30 + k];
                      r0(k / 3, k % 3) = r[39 + k];
                  }
                  Eigen::Quaterniond q(Eigen::Matrix3d(rc * pose.R() * r0.transpose()));
                  return std::vector<double>{q.x() / q.w(), q.y() / q.w()};
              },
              {}};
    } else if (name == "p35pf") {
        *p = {20, 5, nullptr, nullptr, {}, nullptr, nullptr,
              p35pf,
              [](const std::vector<double> &r, const poselib::CameraPose &pose, double f) {
                  // l: the depth of point 0 scaled like Rq and divided by f (its ray is
                  // (u, v, f)), (1 + b^2 + c^2 + d^2) z_0 / f.
                  auto s = quaternion_bcd(pose);
                  double depth = pose.apply(Vec3(r[8], r[9], r[10])).z();
                  return std::vector<double>{s[0], s[1], s[2], s[3] * depth / f, f};
              }};
    } else if (name == "p35pf_nullspace") {
        // PoseLib's p35pf on the same points; a line also holds our data N (12 x 5,
        // row-major) after them, to express PoseLib's cameras in our unknowns.
        *p = {80, 4, nullptr, nullptr, {}, nullptr, nullptr,
              p35pf,
              [](const std::vector<double> &r, const poselib::CameraPose &pose, double f) {
                  // P = diag(f, f, 1) [R | t] column by column in N's basis: x = v[0..4] / v[4].
                  Eigen::Matrix<double, 3, 4> P;
                  P << pose.R(), pose.t;
                  P.topRows(2) *= f;
                  double v[5] = {0, 0, 0, 0, 0};
                  for (int e = 0; e < 12; ++e)
                      for (int j = 0; j < 5; ++j) v[j] += r[20 + 5 * e + j] * P(e % 3, e / 3);
                  return std::vector<double>{v[0] / v[4], v[1] / v[4], v[2] / v[4], v[3] / v[4]};
              }};
    } else {
        return false;
    }
    return true;
}

} // namespace

int main(int argc, char **argv) {
    Problem p;
    if (argc < 4 || !problem(argv[1], &p)) {
        std::fprintf(stderr,
                     "usage: %s p3p|gp3p|up2p_elim|relpose_upright_3pt_elim|relpose_upright_3pt_tan|p3ll|"
                     "relpose_6pt_focal|p2p2pl|p2p2pl_canonical|p35pf|p35pf_nullspace PEER SOLUTIONS\n",
                     argv[0]);
        return 2;
    }
    auto rows = read_rows(argv[2], p.width);
    auto truths = read_rows(argv[3], p.unknowns);
    if (rows.empty() || rows.size() != truths.size()) {
        std::fprintf(stderr, "%zu instances, %zu solutions\n", rows.size(), truths.size());
        return 2;
    }
    int rounds = std::clamp(2000 / int(rows.size()), 3, 25);
    std::vector<double> times;
    size_t poses = 0;
    std::vector<poselib::CameraPose> out;
    poselib::ImagePairVector pairs;
    std::vector<double> focals;
    // One instance's solutions: the number, and, with `convert`, each in our unknowns.
    auto solve = [&](const std::vector<double> &r, std::vector<std::vector<double>> *convert) {
        if (p.solve_pairs) {
            pairs.clear();
            p.solve_pairs(r, &pairs);
            if (convert)
                for (const auto &pair : pairs) convert->push_back(p.ours_pair(r, pair));
            return pairs.size();
        }
        if (p.solve_focal) {
            // p35pf appends to its outputs: both are cleared first.
            out.clear();
            focals.clear();
            p.solve_focal(r, &out, &focals);
            if (convert)
                for (size_t i = 0; i < out.size(); ++i) convert->push_back(p.ours_focal(r, out[i], focals[i]));
            return out.size();
        }
        out.clear();
        p.solve(r, &out);
        if (convert)
            for (const auto &pose : out) convert->push_back(p.ours(r, pose));
        return out.size();
    };
    for (int round = 0; round < rounds; ++round) {
        poses = 0;
        auto start = std::chrono::steady_clock::now();
        for (const auto &r : rows) poses += solve(r, nullptr);
        auto end = std::chrono::steady_clock::now();
        times.push_back(std::chrono::duration<double, std::micro>(end - start).count() / rows.size());
    }
    std::sort(times.begin(), times.end());
    std::printf("%zu instances x %d rounds: %.3f us per call (median round; fastest %.3f), %.2f real solutions per instance\n",
                rows.size(), rounds, times[times.size() / 2], times[0], double(poses) / rows.size());
    std::vector<double> errors;
    for (size_t k = 0; k < rows.size(); ++k) {
        std::vector<std::vector<double>> candidates;
        solve(rows[k], &candidates);
        const auto &t = truths[k];
        std::vector<double> flipped = t;
        for (int i : p.sign_free) flipped[i] = -flipped[i];
        double scale = 1.0;
        for (double x : t) scale = std::max(scale, std::abs(x));
        double best = INFINITY;
        for (const auto &s : candidates) {
            for (const std::vector<double> *truth : {&t, static_cast<const std::vector<double> *>(&flipped)}) {
                double e = 0;
                for (size_t i = 0; i < s.size(); ++i) e += (s[i] - (*truth)[i]) * (s[i] - (*truth)[i]);
                best = std::min(best, std::sqrt(e) / scale);
            }
        }
        errors.push_back(best);
    }
    size_t recovered = std::count_if(errors.begin(), errors.end(), [](double e) { return e <= 1e-6; });
    std::sort(errors.begin(), errors.end());
    auto lg = [](double e) { return std::log10(std::max(e, 1e-17)); };
    std::printf("planted solution recovered (to 1e-6): %zu of %zu; error log10 median %.2f, p99 %.2f\n", recovered,
                errors.size(), lg(errors[errors.size() / 2]),
                lg(errors[std::min(errors.size() - 1, errors.size() * 99 / 100)]));
    return 0;
}
