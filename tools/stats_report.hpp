// `filmgrain stats` as functions: the report of a clean/grainy pair of files, and the
// statistics of one clean plane and its grain (the Python module's stats on arrays).
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "core/float_plane.hpp"

namespace filmgrain::cli {

struct StatsOptions {
    std::string clean, grainy;
    bool json = false;
    int max_lag = 4, channel = 0, bins = 16, spectrum_block = 32;
    std::vector<int> blocks{8, 16, 32, 64};
    std::vector<int> periods{32, 64};
    RawVideoOptions raw;
};

void add_stats_options(CLI::App* sub, StatsOptions& o);
// The JSON `filmgrain stats --json` prints. Throws Error naming the file or option.
nlohmann::json grain_statistics_report(const StatsOptions& options);
nlohmann::json statistics_json(const FloatPlane& clean, const FloatPlane& grain, const StatsOptions& options);

}  // namespace filmgrain::cli
