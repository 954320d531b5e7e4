#pragma once
// Owners of driver objects. Each holds the device's primary context (shared) and makes it current
// around its own calls, so a map handle may outlive the backend that made it and backends on
// several threads each push their context for the length of a call.
#include <memory>
#include <string>
#include <utility>

#include "cu_api.hpp"

namespace trn::cuda {

// A device's primary context, retained while anything on the device lives.
class Context {
public:
    explicit Context(int ordinal);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;
    CUdevice device() const { return device_; }
    CUcontext get() const { return context_; }

private:
    CUdevice device_ = 0;
    CUcontext context_ = nullptr;
};

// Makes the context current on this thread for its scope (and the previous one current again after).
class ContextScope {
public:
    explicit ContextScope(const Context& context);
    ~ContextScope();
    ContextScope(const ContextScope&) = delete;
    ContextScope& operator=(const ContextScope&) = delete;
};

// One cuMemAlloc allocation; `what` names it in errors.
class DeviceMemory {
public:
    DeviceMemory() = default;
    DeviceMemory(std::shared_ptr<Context> context, std::size_t bytes, const std::string& what);
    ~DeviceMemory() { reset(); }
    DeviceMemory(DeviceMemory&& o) noexcept { *this = std::move(o); }
    DeviceMemory& operator=(DeviceMemory&& o) noexcept;
    void reset();
    CUdeviceptr get() const { return ptr_; }
    std::size_t bytes() const { return bytes_; }

private:
    std::shared_ptr<Context> context_;
    CUdeviceptr ptr_ = 0;
    std::size_t bytes_ = 0;
};

// A buffer kept between calls that only grows, so steady-state calls allocate nothing.
class GrowingBuffer {
public:
    // Makes the buffer hold at least `bytes`; true when it was reallocated (its content is then gone).
    bool ensure(const std::shared_ptr<Context>& context, std::size_t bytes, const std::string& what);
    CUdeviceptr get() const { return memory_.get(); }

private:
    DeviceMemory memory_;
};

class Stream {
public:
    explicit Stream(std::shared_ptr<Context> context);
    ~Stream();
    Stream(const Stream&) = delete;
    Stream& operator=(const Stream&) = delete;
    CUstream get() const { return stream_; }

private:
    std::shared_ptr<Context> context_;
    CUstream stream_ = nullptr;
};

class Event {
public:
    explicit Event(std::shared_ptr<Context> context);
    ~Event();
    Event(const Event&) = delete;
    Event& operator=(const Event&) = delete;
    CUevent get() const { return event_; }

private:
    std::shared_ptr<Context> context_;
    CUevent event_ = nullptr;
};

// A module loaded from a fat binary (the driver picks the cubin or compiles the PTX). Throws
// trn::Error with the JIT log and `code` (fatbin_contents.hpp's choice for the device) when it fails.
class Module {
public:
    Module(std::shared_ptr<Context> context, const void* image, const std::string& file, const std::string& code);
    ~Module();
    Module(const Module&) = delete;
    Module& operator=(const Module&) = delete;
    CUfunction function(const char* name) const;

private:
    std::shared_ptr<Context> context_;
    CUmodule module_ = nullptr;
    std::string file_;
};

}  // namespace trn::cuda
