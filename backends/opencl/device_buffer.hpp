#pragma once
// A device buffer that keeps its allocation between calls and only grows, so steady-state
// scoring and Sobel calls allocate nothing.
#include <string>

#include "cl_api.hpp"
#include "trn/error.hpp"

namespace trn::opencl {

class DeviceBuffer {
public:
    // Makes the buffer hold at least `bytes`. Returns true when it had to be reallocated (its old
    // content is then gone). `what` names the buffer in errors.
    bool ensure(cl_context context, std::size_t bytes, cl_mem_flags flags, cl_ulong max_alloc, const char* what) {
        if (bytes <= capacity_ && mem_) return false;
        if (bytes > max_alloc)
            throw Error("OpenCL: the " + std::string(what) + " needs " + std::to_string(bytes >> 20) +
                        " MiB, more than the device's largest buffer (CL_DEVICE_MAX_MEM_ALLOC_SIZE = " +
                        std::to_string(max_alloc >> 20) + " MiB)");
        // Grow with headroom so a slowly rising particle count does not reallocate every call.
        std::size_t grown = capacity_ + capacity_ / 2;
        if (grown < bytes || grown > max_alloc) grown = bytes;
        mem_.reset();
        capacity_ = 0;
        cl_int err = CL_SUCCESS;
        mem_.reset(clCreateBuffer(context, flags, grown, nullptr, &err));
        check(err, "clCreateBuffer(" + std::string(what) + ", " + std::to_string(grown) + " bytes)");
        capacity_ = grown;
        return true;
    }
    cl_mem get() const { return mem_.get(); }

private:
    MemHandle mem_;
    std::size_t capacity_ = 0;
};

}  // namespace trn::opencl
