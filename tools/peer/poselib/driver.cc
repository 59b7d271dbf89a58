// Times PoseLib on the instances written by `peer_bench write DIR` (solver/examples/
// peer_bench.rs) and prints the same lines as `peer_bench time DIR`, prefixed "poselib".
// Our own code, compiled against a PoseLib checkout the user provides (run.sh).
//
//   driver DIR [ROUNDS]
//
// Work per call, as on our side: essential matrices from 5 bearings (relpose_5pt, the
// essential-matrix overload); poses from 5 bearings (relpose_5pt, the CameraPose overload,
// which decomposes each essential matrix and checks cheirality on the five points); the
// estimator (estimate_relative_pose: exactly 200 RANSAC iterations, Sampson threshold 2 px,
// LO and the final bundle refinement at PoseLib's defaults).
#include <PoseLib/poselib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Five {
    std::vector<Eigen::Vector3d> x1, x2;
};

struct Pair {
    double fx, fy, cx, cy;
    Eigen::Matrix3d R;
    Eigen::Vector3d t;
    std::vector<poselib::Point2D> p1, p2;
};

template <class F> double time_us(int rounds, int calls, F f) {
    std::vector<double> t;
    for (int r = 0; r < rounds; ++r) {
        auto start = std::chrono::steady_clock::now();
        for (int k = 0; k < calls; ++k) f(k);
        auto end = std::chrono::steady_clock::now();
        t.push_back(std::chrono::duration<double, std::micro>(end - start).count() / calls);
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

double rotation_error_deg(const Eigen::Matrix3d &a, const Eigen::Matrix3d &b) {
    double c = std::clamp(((a.transpose() * b).trace() - 1.0) / 2.0, -1.0, 1.0);
    return std::acos(c) * 180.0 / M_PI;
}

double translation_error_deg(const Eigen::Vector3d &a, const Eigen::Vector3d &b) {
    double c = std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0);
    return std::acos(c) * 180.0 / M_PI;
}

} // namespace

int main(int argc, char **argv) {
    if (argc < 2) {
        std::cerr << "usage: driver DIR [ROUNDS]\n";
        return 2;
    }
    std::string dir = argv[1];
    int rounds = argc > 2 ? std::atoi(argv[2]) : 5;
    std::vector<Five> five;
    {
        std::ifstream in(dir + "/five_point.txt");
        if (!in) {
            std::cerr << dir << "/five_point.txt: cannot open\n";
            return 2;
        }
        std::string line;
        while (std::getline(in, line)) {
            std::istringstream s(line);
            Five f;
            for (int k = 0; k < 10; ++k) {
                Eigen::Vector3d b;
                s >> b(0) >> b(1) >> b(2);
                (k < 5 ? f.x1 : f.x2).push_back(b);
            }
            five.push_back(f);
        }
    }
    std::vector<Pair> pairs;
    {
        std::ifstream in(dir + "/pairs.txt");
        if (!in) {
            std::cerr << dir << "/pairs.txt: cannot open\n";
            return 2;
        }
        int n;
        while (in >> n) {
            Pair p;
            in >> p.fx >> p.fy >> p.cx >> p.cy;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) in >> p.R(i, j);
            in >> p.t(0) >> p.t(1) >> p.t(2);
            for (int i = 0; i < n; ++i) {
                poselib::Point2D a, b;
                in >> a(0) >> a(1) >> b(0) >> b(1);
                p.p1.push_back(a);
                p.p2.push_back(b);
            }
            pairs.push_back(p);
        }
    }
    std::vector<Eigen::Matrix3d> es;
    volatile size_t sink = 0;
    double e_us = time_us(rounds, 30000, [&](int k) {
        const Five &f = five[k % five.size()];
        es.clear();
        poselib::relpose_5pt(f.x1, f.x2, &es);
        sink = sink + es.size();
    });
    std::vector<poselib::CameraPose> poses;
    double p_us = time_us(rounds, 30000, [&](int k) {
        const Five &f = five[k % five.size()];
        poses.clear();
        poselib::relpose_5pt(f.x1, f.x2, &poses);
        sink = sink + poses.size();
    });
    poselib::RelativePoseOptions opt;
    opt.ransac.min_iterations = 200;
    opt.ransac.max_iterations = 200;
    opt.max_error = 2.0;
    std::vector<double> rot, tra;
    double est_us = time_us(rounds, pairs.size(), [&](int k) {
        const Pair &p = pairs[k];
        poselib::Camera cam("PINHOLE", {p.fx, p.fy, p.cx, p.cy}, 1920, 1080);
        poselib::CameraPose pose;
        std::vector<char> inliers;
        poselib::estimate_relative_pose(p.p1, p.p2, cam, cam, opt, &pose, &inliers);
        if (rot.size() < pairs.size()) {
            rot.push_back(rotation_error_deg(p.R, pose.R()));
            tra.push_back(translation_error_deg(p.t, pose.t));
        }
    });
    auto mean = [](const std::vector<double> &v) {
        double s = 0;
        for (double x : v) s += x;
        return v.empty() ? 0.0 : s / v.size();
    };
    std::printf("poselib essential_from_5_bearings_us %.3f\n", e_us);
    std::printf("poselib poses_from_5_bearings_us %.3f\n", p_us);
    std::printf("poselib estimator_200_iterations_us %.1f\n", est_us);
    std::printf("poselib estimator_mean_errors_deg rotation %.4f translation %.4f solved %zu\n", mean(rot),
                mean(tra), rot.size());
    return 0;
}
