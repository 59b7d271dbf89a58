// Shared by the peer drivers: the rows of a whitespace-separated text file of numbers
// (instances, planted solutions), keeping the lines with exactly `width` values.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

inline std::vector<std::vector<double>> read_rows(const char *path, size_t width) {
    std::ifstream in(path);
    std::vector<std::vector<double>> rows;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream s(line);
        std::vector<double> row;
        double x;
        while (s >> x) row.push_back(x);
        if (row.size() == width) rows.push_back(row);
    }
    return rows;
}
