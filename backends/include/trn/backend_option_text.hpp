#pragma once
// BackendOptions from text, one field per NAME=VALUE, for a program that takes backend settings
// from its command line, a configuration file or its environment. The library reads none of those
// itself: backend_options_from_variables maps the TRN_* variables onto these names from values a
// program looks up (the trnkit CLI, the test and benchmark mains: std::getenv).
//
// Names are the fields' paths in BackendOptions; values are checked here, before any backend is
// created (the backends still check their own ranges, e.g. powers of two, when they are created):
//   default_device.FAMILY        any text: an index or a device name piece ("1", "pocl")
//   cpu.threads                  whole number 1..4096
//   cpu.simd                     on|off (also 1|0, true|false)
//   opencl.work_group            whole number 1..65536
//   opencl.program_cache_dir     a folder; empty: no disk cache
//   vulkan.work_group            whole number 1..1024
//   vulkan.particles_per_group   whole number 1..16
//   vulkan.quad_maps, vulkan.subgroups, vulkan.force_staging, vulkan.validation   on|off
//   vulkan.pipeline_cache_dir    a folder; empty: no disk cache
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "trn/backend_options.hpp"
#include "trn/error.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

// A name or value set_backend_option refuses. what() is "NAME='VALUE': PROBLEM"; the parts are
// kept so that a program can say which of its own inputs (a variable, a flag) was at fault.
class BackendOptionError : public Error {
public:
    BackendOptionError(std::string name, std::string value, std::string problem);
    const std::string& name() const { return name_; }
    const std::string& value() const { return value_; }
    const std::string& problem() const { return problem_; }

private:
    std::string name_, value_, problem_;
};

struct BackendOptionName {
    std::string name;    // "cpu.threads"; "default_device.FAMILY" stands for every family
    std::string values;  // what the value may be, for help texts
};
// Every name set_backend_option takes, in BackendOptions order.
const std::vector<BackendOptionName>& backend_option_names();

// Sets the field `name` of `options` from `value`; throws BackendOptionError for an unknown name
// or a value that is not one the field takes.
void set_backend_option(BackendOptions& options, std::string_view name, std::string_view value);
// The same from "NAME=VALUE".
void set_backend_option(BackendOptions& options, std::string_view assignment);

// The TRN_* variables (README.md's table) as BackendOptions, each value looked up through `lookup`
// (nullptr or "": unset). The library reads no environment itself: a program passes std::getenv
// (the trnkit CLI, the test and benchmark mains), anything else a table of its own. A refused value
// throws trn::Error naming the variable ("TRN_CPU_THREADS='abc': ...").
using VariableLookup = std::function<const char*(const char* name)>;
BackendOptions backend_options_from_variables(const VariableLookup& lookup);

}  // namespace trn
TRN_API_END
