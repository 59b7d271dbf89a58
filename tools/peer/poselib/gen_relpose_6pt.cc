// Runs PoseLib's gen_relpose_6pt on instances of templates/large/gen_relpose_6pt.mp (one per
// line: p1[6], d1[6], p2[6], d2[6] as x y z; tools/gen_relpose_6pt_instances.py writes
// them) and prints the figures tools/emitted_solver/main.rs prints for our emitted solver:
// per-call time and how many planted solutions (q1 q2 q3 t1 t2 t3, q the Cayley vector of
// R, X2 = R X1 + t) are recovered to 1e-6 relative. Our own code, compiled against a
// PoseLib checkout the user provides (gen_relpose_6pt.sh).
//
//   gen_relpose_6pt INSTANCES SOLUTIONS
//
// PoseLib's solver returns the poses that pass its cheirality check, each refined by
// Newton steps on the six constraints; ours (with `option newton = 2`) returns every real
// solution, each polished by up to two Gauss-Newton steps.
#include <PoseLib/poselib.h>

#include "rows.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Instance {
    std::vector<Eigen::Vector3d> p1, x1, p2, x2;
};

} // namespace

int main(int argc, char **argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s INSTANCES SOLUTIONS\n", argv[0]);
        return 2;
    }
    auto rows = read_rows(argv[1], 72);
    auto truths = read_rows(argv[2], 6);
    if (rows.empty() || rows.size() != truths.size()) {
        std::fprintf(stderr, "%zu instances, %zu solutions\n", rows.size(), truths.size());
        return 2;
    }
    std::vector<Instance> data;
    for (const auto &r : rows) {
        Instance in;
        auto v = [&](int block, int i) { return Eigen::Vector3d(r[18 * block + 3 * i], r[18 * block + 3 * i + 1], r[18 * block + 3 * i + 2]); };
        for (int i = 0; i < 6; ++i) {
            in.p1.push_back(v(0, i));
            in.x1.push_back(v(1, i));
            in.p2.push_back(v(2, i));
            in.x2.push_back(v(3, i));
        }
        data.push_back(in);
    }
    int rounds = std::clamp(2000 / int(data.size()), 3, 25);
    std::vector<double> times;
    size_t poses = 0;
    std::vector<poselib::CameraPose> out;
    for (int round = 0; round < rounds; ++round) {
        poses = 0;
        auto start = std::chrono::steady_clock::now();
        for (const auto &in : data) {
            poselib::gen_relpose_6pt(in.p1, in.x1, in.p2, in.x2, &out);
            poses += out.size();
        }
        auto end = std::chrono::steady_clock::now();
        times.push_back(std::chrono::duration<double, std::micro>(end - start).count() / data.size());
    }
    std::sort(times.begin(), times.end());
    std::printf("%zu instances x %d rounds: %.1f us per call (median round; fastest %.1f), %.2f poses per instance\n",
                data.size(), rounds, times[times.size() / 2], times[0], double(poses) / data.size());
    std::vector<double> errors;
    for (size_t k = 0; k < data.size(); ++k) {
        const auto &in = data[k];
        poselib::gen_relpose_6pt(in.p1, in.x1, in.p2, in.x2, &out);
        const auto &t = truths[k];
        double scale = 1.0;
        for (double x : t) scale = std::max(scale, std::abs(x));
        double best = INFINITY;
        for (const auto &pose : out) {
            double w = pose.q(0);
            double s[6] = {pose.q(1) / w, pose.q(2) / w, pose.q(3) / w, pose.t(0), pose.t(1), pose.t(2)};
            double e = 0;
            for (int i = 0; i < 6; ++i) e += (s[i] - t[i]) * (s[i] - t[i]);
            best = std::min(best, std::sqrt(e) / scale);
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
