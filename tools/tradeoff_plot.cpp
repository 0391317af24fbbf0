#include "tradeoff_plot.hpp"

#include "filmgrain/error.hpp"
#include "image_module.hpp"
#include "io/output_file.hpp"

namespace filmgrain::cli {

bool write_tradeoff_plot(const std::string& path, const std::vector<PlotPoint>& points, std::string* why) {
    std::string reason;
    const ImageModule* m = image_module(&reason);
    if (m) {
        try {
            OutputFile file(path);
            reason = m->write_plot(file.write_path(), image_format_of(path), points);
            if (reason.empty()) {
                file.commit();
                return true;
            }
        } catch (const Error& e) {
            reason = e.what();
        }
    }
    if (why) *why = reason;
    return false;
}

}  // namespace filmgrain::cli
