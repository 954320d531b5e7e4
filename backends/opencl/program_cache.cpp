// Program building and the on-disk binary cache; see program_cache.hpp.
#include "program_cache.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

namespace trn::opencl {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr std::string_view kMagic = "trnkit-opencl-binary v1\n";

// FNV-1a: a short, stable file name for a long key (the key itself is checked on load).
std::string fnv1a_hex(std::string_view text) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (unsigned char c : text) h = (h ^ c) * 0x100000001b3ull;
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

std::string device_identity(const DeviceRef& device) {
    return "device " + device_string(device.device, CL_DEVICE_NAME) + "\ndevice version " +
           device_string(device.device, CL_DEVICE_VERSION) + "\ndriver " + device_string(device.device, CL_DRIVER_VERSION) +
           "\nplatform " + platform_string(device.platform, CL_PLATFORM_NAME) + "\nplatform version " +
           platform_string(device.platform, CL_PLATFORM_VERSION) + "\n";
}

std::string build_log(cl_program program, cl_device_id device) {
    std::size_t size = 0;
    if (clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size) != CL_SUCCESS) return "(no build log)";
    std::string log(size, '\0');
    if (clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr) != CL_SUCCESS)
        return "(no build log)";
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    return log.empty() ? "(empty build log)" : log;
}

// Writes `bytes` to `path` through a temporary file in the same folder and a rename, so a
// concurrent reader sees either the old entry or the complete new one.
void write_atomically(const fs::path& path, const std::string& bytes) {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) return;  // an unwritable cache only costs the next start a rebuild
    const fs::path tmp = path.string() + ".tmp." + std::to_string(::getpid());
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        if (!out) {
            fs::remove(tmp, ec);
            return;
        }
    }
    fs::rename(tmp, path, ec);
    if (ec) fs::remove(tmp, ec);
}

std::optional<std::string> read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The binary stored for `key`, when the entry exists and really is for this key.
std::optional<std::string> load_entry(const fs::path& path, const std::string& key) {
    const auto data = read_file(path);
    if (!data) return std::nullopt;
    const std::string header = std::string(kMagic) + std::to_string(key.size()) + "\n" + key;
    if (data->size() <= header.size() || data->compare(0, header.size(), header) != 0) return std::nullopt;
    return data->substr(header.size());
}

void store_entry(const fs::path& path, const std::string& key, const std::string& binary) {
    write_atomically(path, std::string(kMagic) + std::to_string(key.size()) + "\n" + key + binary);
}

std::string program_binary(cl_program program) {
    std::size_t size = 0;
    check(clGetProgramInfo(program, CL_PROGRAM_BINARY_SIZES, sizeof size, &size, nullptr),
          "clGetProgramInfo(CL_PROGRAM_BINARY_SIZES)");
    std::string binary(size, '\0');
    unsigned char* ptr = reinterpret_cast<unsigned char*>(binary.data());
    check(clGetProgramInfo(program, CL_PROGRAM_BINARIES, sizeof ptr, &ptr, nullptr), "clGetProgramInfo(CL_PROGRAM_BINARIES)");
    return binary;
}

// A program from a cached binary, or nothing when the driver refuses it (then we rebuild).
ProgramHandle program_from_binary(cl_context context, const DeviceRef& device, const std::string& binary,
                                  const std::string& options) {
    const unsigned char* ptr = reinterpret_cast<const unsigned char*>(binary.data());
    const std::size_t size = binary.size();
    cl_int status = CL_SUCCESS, err = CL_SUCCESS;
    ProgramHandle p(clCreateProgramWithBinary(context, 1, &device.device, &size, &ptr, &status, &err));
    if (err != CL_SUCCESS || status != CL_SUCCESS) return {};
    if (clBuildProgram(p.get(), 1, &device.device, options.c_str(), nullptr, nullptr) != CL_SUCCESS) return {};
    return p;
}

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

}  // namespace

ProgramCacheSettings program_cache_settings(const BackendOptions::OpenCl& options) {
    ProgramCacheSettings s;
    s.dir = options.program_cache_dir;
    s.enabled = !s.dir.empty();
    return s;
}

std::string program_cache_key(const DeviceRef& device, std::string_view source_sha256, const std::string& options) {
    return "source sha256 " + std::string(source_sha256) + "\noptions " + options + "\n" + device_identity(device);
}

fs::path program_cache_path(const ProgramCacheSettings& cache, std::string_view file, const std::string& key) {
    std::string stem(file);
    if (const auto dot = stem.rfind('.'); dot != std::string::npos) stem.resize(dot);
    return cache.dir / (stem + "-" + fnv1a_hex(key) + ".bin");
}

BuiltProgram build_program(cl_context context, const DeviceRef& device, std::string_view file, std::string_view source,
                           std::string_view source_sha256, const std::string& options,
                           const ProgramCacheSettings& cache) {
    const auto t0 = Clock::now();
    BuiltProgram built;
    const std::string key = program_cache_key(device, source_sha256, options);
    const fs::path entry = cache.enabled ? program_cache_path(cache, file, key) : fs::path();
    if (cache.enabled)
        if (const auto binary = load_entry(entry, key)) {
            built.program = program_from_binary(context, device, *binary, options);
            if (built.program) {
                built.from_cache = true;
                built.build_ms = ms_since(t0);
                return built;
            }
        }

    const char* text = source.data();
    const std::size_t length = source.size();
    cl_int err = CL_SUCCESS;
    built.program.reset(clCreateProgramWithSource(context, 1, &text, &length, &err));
    check(err, "clCreateProgramWithSource(" + std::string(file) + ")");
    err = clBuildProgram(built.program.get(), 1, &device.device, options.c_str(), nullptr, nullptr);
    if (err != CL_SUCCESS)
        throw Error("OpenCL clBuildProgram(" + std::string(file) + ") failed on device '" +
                    device_string(device.device, CL_DEVICE_NAME) + "' with options '" + options + "': " + error_name(err) +
                    " (" + std::to_string(err) + ")\nbuild log:\n" + build_log(built.program.get(), device.device));
    built.build_ms = ms_since(t0);
    if (cache.enabled) store_entry(entry, key, program_binary(built.program.get()));
    return built;
}

namespace {

fs::path timings_path(const ProgramCacheSettings& cache, const DeviceRef& device) {
    return cache.dir / ("device-" + fnv1a_hex(device_identity(device)) + ".timings");
}

}  // namespace

void record_build_time(const ProgramCacheSettings& cache, const DeviceRef& device, bool warm, double ms) {
    if (!cache.enabled) return;
    const fs::path path = timings_path(cache, device);
    double cold_ms = -1, warm_ms = -1;
    if (const auto old = read_file(path)) {
        std::istringstream in(*old);
        in >> cold_ms >> warm_ms;
        if (!in) cold_ms = warm_ms = -1;
    }
    (warm ? warm_ms : cold_ms) = ms;
    write_atomically(path, std::to_string(cold_ms) + " " + std::to_string(warm_ms) + "\n");
}

std::string recorded_build_times(const ProgramCacheSettings& cache, const DeviceRef& device) {
    if (!cache.enabled) return "";
    const auto data = read_file(timings_path(cache, device));
    if (!data) return "";
    std::istringstream in(*data);
    double cold_ms = -1, warm_ms = -1;
    if (!(in >> cold_ms >> warm_ms)) return "";
    auto text = [](double ms) { return ms < 0 ? std::string("not yet measured") : std::to_string(static_cast<long>(ms + 0.5)) + " ms"; };
    return "cold build " + text(cold_ms) + ", warm (cached) build " + text(warm_ms);
}

}  // namespace trn::opencl
