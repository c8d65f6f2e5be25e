// Placeholder while the ASF/AMC importer is being written.
#include "motion/asf_amc.hpp"
#include "core/error.hpp"
namespace mimic {
AxisConvention asf_default_axes() { return AxisConvention{"y", "z", 0.0}; }
AsfSkeleton parse_asf(std::string_view, const std::string& source, const AxisConvention&) { throw Error(source + ": ASF not implemented yet"); }
AsfSkeleton load_asf(const std::filesystem::path& path, const AxisConvention&) { throw Error(path.string() + ": ASF not implemented yet"); }
Clip parse_amc(std::string_view, const std::string& source, const AsfSkeleton&, double) { throw Error(source + ": AMC not implemented yet"); }
Clip load_amc(const std::filesystem::path& path, const AsfSkeleton&, double) { throw Error(path.string() + ": AMC not implemented yet"); }
std::filesystem::path guess_asf(const std::filesystem::path&) { return {}; }
}  // namespace mimic
