#pragma once
// The OpenCL C API as trnkit uses it: OpenCL 1.2 entry points only, so any 1.2+ driver works.
#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>

#include <concepts>
#include <string>
#include <utility>

namespace trn::opencl {

// "CL_OUT_OF_RESOURCES" for -5 and so on; "unknown OpenCL error" for codes it does not know.
const char* error_name(cl_int code);

// Throws trn::Error "OpenCL <call> failed: <NAME> (<code>)".
[[noreturn]] void throw_error(cl_int code, const std::string& call);

// Throws (as above) when code is not CL_SUCCESS.
inline void check(cl_int code, const char* call) {
    if (code != CL_SUCCESS) throw_error(code, call);
}
inline void check(cl_int code, const std::string& call) {
    if (code != CL_SUCCESS) throw_error(code, call);
}
// The call's description is only built on failure: steady-state calls must not allocate.
template <std::invocable F>
void check(cl_int code, F&& describe_call) {
    if (code != CL_SUCCESS) throw_error(code, describe_call());
}

// Owns one OpenCL object and releases it with its clRelease* function.
template <typename T, cl_int (*Release)(T)>
class Handle {
public:
    Handle() = default;
    explicit Handle(T h) : h_(h) {}
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    Handle(Handle&& o) noexcept : h_(std::exchange(o.h_, nullptr)) {}
    Handle& operator=(Handle&& o) noexcept {
        if (this != &o) {
            reset();
            h_ = std::exchange(o.h_, nullptr);
        }
        return *this;
    }
    ~Handle() { reset(); }
    void reset(T h = nullptr) {
        if (h_) Release(h_);
        h_ = h;
    }
    T get() const { return h_; }
    explicit operator bool() const { return h_ != nullptr; }

private:
    T h_ = nullptr;
};

using ContextHandle = Handle<cl_context, clReleaseContext>;
using QueueHandle = Handle<cl_command_queue, clReleaseCommandQueue>;
using ProgramHandle = Handle<cl_program, clReleaseProgram>;
using KernelHandle = Handle<cl_kernel, clReleaseKernel>;
using MemHandle = Handle<cl_mem, clReleaseMemObject>;
using EventHandle = Handle<cl_event, clReleaseEvent>;

}  // namespace trn::opencl
