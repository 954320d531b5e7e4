// Driver object owners; see cuda_resources.hpp. Destructors ignore errors: they run during unwinding
// and after a sticky device error, when the driver refuses everything.
#include "cuda_resources.hpp"

#include <algorithm>
#include <cstdint>

#include "trn/error.hpp"

namespace trn::cuda {

Context::Context(int ordinal) {
    const DriverApi& api = driver();
    check(api.cuDeviceGet(&device_, ordinal), "cuDeviceGet(" + std::to_string(ordinal) + ")");
    check(api.cuDevicePrimaryCtxRetain(&context_, device_), "cuDevicePrimaryCtxRetain(cuda:" + std::to_string(ordinal) + ")");
}

Context::~Context() { driver().cuDevicePrimaryCtxRelease(device_); }

ContextScope::ContextScope(const Context& context) { check(driver().cuCtxPushCurrent(context.get()), "cuCtxPushCurrent"); }

ContextScope::~ContextScope() {
    CUcontext popped = nullptr;
    driver().cuCtxPopCurrent(&popped);
}

DeviceMemory::DeviceMemory(std::shared_ptr<Context> context, std::size_t bytes, const std::string& what)
    : context_(std::move(context)), bytes_(bytes) {
    const ContextScope scope(*context_);
    check(driver().cuMemAlloc(&ptr_, bytes == 0 ? 1 : bytes), "cuMemAlloc(" + what + ", " + std::to_string(bytes) + " bytes)");
}

DeviceMemory& DeviceMemory::operator=(DeviceMemory&& o) noexcept {
    if (this != &o) {
        reset();
        context_ = std::move(o.context_);
        ptr_ = std::exchange(o.ptr_, 0);
        bytes_ = std::exchange(o.bytes_, 0);
    }
    return *this;
}

void DeviceMemory::reset() {
    if (ptr_) {
        try {
            const ContextScope scope(*context_);
            driver().cuMemFree(ptr_);
        } catch (const Error&) {  // the context could not be made current: the memory goes with it
        }
    }
    ptr_ = 0;
    bytes_ = 0;
    context_.reset();
}

bool GrowingBuffer::ensure(const std::shared_ptr<Context>& context, std::size_t bytes, const std::string& what) {
    if (memory_.get() && bytes <= memory_.bytes()) return false;
    // Headroom, so a slowly rising particle count does not reallocate every call.
    const std::size_t grown = std::max(bytes, memory_.bytes() + memory_.bytes() / 2);
    memory_.reset();
    try {
        memory_ = DeviceMemory(context, grown, what);
    } catch (const Error&) {
        if (grown == bytes) throw;
        memory_ = DeviceMemory(context, bytes, what);
    }
    return true;
}

Stream::Stream(std::shared_ptr<Context> context) : context_(std::move(context)) {
    const ContextScope scope(*context_);
    check(driver().cuStreamCreate(&stream_, CU_STREAM_NON_BLOCKING), "cuStreamCreate");
}

Stream::~Stream() {
    try {
        const ContextScope scope(*context_);
        driver().cuStreamDestroy(stream_);
    } catch (const Error&) {
    }
}

Event::Event(std::shared_ptr<Context> context) : context_(std::move(context)) {
    const ContextScope scope(*context_);
    check(driver().cuEventCreate(&event_, CU_EVENT_DEFAULT), "cuEventCreate");
}

Event::~Event() {
    try {
        const ContextScope scope(*context_);
        driver().cuEventDestroy(event_);
    } catch (const Error&) {
    }
}

Module::Module(std::shared_ptr<Context> context, const void* image, const std::string& file, const std::string& code)
    : context_(std::move(context)), file_(file) {
    const ContextScope scope(*context_);
    char log[4096] = {};
    CUjit_option options[] = {CU_JIT_ERROR_LOG_BUFFER, CU_JIT_ERROR_LOG_BUFFER_SIZE_BYTES};
    void* values[] = {log, reinterpret_cast<void*>(std::uintptr_t(sizeof log - 1))};
    const CUresult r = driver().cuModuleLoadDataEx(&module_, image, 2, options, values);
    if (r != CUDA_SUCCESS)
        throw Error("cuda: cuModuleLoadDataEx(" + file + ") failed: " + result_text(driver(), r) + "; code for this device: " + code +
                    (log[0] ? "; JIT log: " + std::string(log) : std::string()));
}

Module::~Module() {
    try {
        const ContextScope scope(*context_);
        driver().cuModuleUnload(module_);
    } catch (const Error&) {
    }
}

CUfunction Module::function(const char* name) const {
    CUfunction f = nullptr;
    check(driver().cuModuleGetFunction(&f, module_, name), "cuModuleGetFunction(" + file_ + ", " + name + ")");
    return f;
}

}  // namespace trn::cuda
