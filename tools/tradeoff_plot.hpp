// The speed/accuracy plot of `filmgrain tradeoff`: log-log axes, one labelled point per method.
#pragma once
#include <string>
#include <vector>

namespace filmgrain::cli {

struct PlotPoint {
    std::string label;
    double throughput = 0;  // Mpixel/s, x axis
    double error = 0;       // y axis
};

// Writes the plot (PNG, or another format by the name's extension) through OutputFile; the
// drawing itself is OpenImageIO's, in the image module (image_module/oiio_stills_and_plot.cpp).
// Returns false with a reason when it cannot.
bool write_tradeoff_plot(const std::string& path, const std::vector<PlotPoint>& points, std::string* why);

}  // namespace filmgrain::cli
