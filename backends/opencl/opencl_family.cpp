// Registers OpenCL devices with the backend registry.
#include "opencl_family.hpp"

#include "cl_devices.hpp"
#include "opencl_backend.hpp"
#include "program_cache.hpp"

namespace trn {

BackendFamily opencl_family() {
    BackendFamily f;
    f.name = "opencl";
    f.description = "OpenCL C kernels (any OpenCL 1.2+ device, CPU devices such as PoCL included)";
    f.list_devices = [](const BackendOptions& options, std::string& why_none) {
        const std::vector<opencl::DeviceRef> refs = opencl::enumerate_devices(why_none);
        const opencl::ProgramCacheSettings cache = opencl::program_cache_settings(options.opencl);
        std::vector<DeviceInfo> infos;
        for (std::size_t i = 0; i < refs.size(); ++i) {
            DeviceInfo info = opencl::describe_device(refs[i], static_cast<int>(i));
            const std::string times = opencl::recorded_build_times(cache, refs[i]);
            info.details += "; program cache " + (cache.enabled ? cache.dir.string() : std::string("off"));
            if (cache.enabled) info.details += times.empty() ? " (no build recorded yet)" : " (" + times + ")";
            infos.push_back(std::move(info));
        }
        return infos;
    };
    f.create = [](int index, const BackendOptions& options) -> std::unique_ptr<Backend> {
        std::string why_none;
        const std::vector<opencl::DeviceRef> refs = opencl::enumerate_devices(why_none);
        if (index < 0 || index >= static_cast<int>(refs.size()))
            throw BackendUnavailable("opencl:" + std::to_string(index) + " does not exist (" + std::to_string(refs.size()) +
                                     " OpenCL device(s)" + (why_none.empty() ? "" : ": " + why_none) + ")");
        return opencl::make_opencl_backend(refs[static_cast<std::size_t>(index)], index, options.opencl);
    };
    return f;
}

}  // namespace trn
