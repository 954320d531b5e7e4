#pragma once
// _trnkit.Backend, Map, Plan and Sampling: the compiled half of trnkit.Backend (python/trnkit/_backend.py
// adds the keywords' checks, the docstrings and the context manager). Other bindings that take a
// backend or a map (the Localizer) use PyBackend / PyMap from here.
#include <pybind11/pybind11.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "trn/backend.hpp"

namespace trn::py {

struct PyMap;

// Something built on a backend that holds device memory of its own (a Localizer's map): the
// backend's close() releases it first.
struct BackendUser {
    virtual ~BackendUser() = default;
    virtual void release_device() = 0;  // called with the backend's mutex held
};

// A trn::Backend is not thread-safe: every call on it holds `mutex` (with the GIL released).
// close() releases the maps' device memory and then the backend; afterwards `impl` is null.
struct PyBackend {
    std::unique_ptr<Backend> impl;
    std::string name;  // kept after close() for messages and repr
    std::mutex mutex;
    std::vector<std::weak_ptr<PyMap>> maps;  // guarded by mutex; released by close()
    std::vector<std::weak_ptr<BackendUser>> users;  // guarded by mutex; released by close()

    // The backend, or trn::Error when it is closed; call with `mutex` held.
    Backend& open_backend() const;
};

// A map keeps its backend alive (declared first: released after the map).
struct PyMap {
    std::shared_ptr<PyBackend> backend;
    MapHandle handle;  // null once the backend was closed
    int width = 0, height = 0;

    // The handle, or trn::Error when its backend was closed; call with backend->mutex held.
    const MapHandle& open_handle() const;
};

void register_backend(pybind11::module_& m);

}  // namespace trn::py
