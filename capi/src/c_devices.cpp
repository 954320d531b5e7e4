// trn_devices: every usable device of the default registry, as the `trnkit devices` list has them.
#include "c_handles.hpp"
#include "c_status.hpp"
#include "trn/registry.hpp"

using trn::capi::guarded;
using trn::capi::InvalidArgument;
using trn::capi::require_pointer;

extern "C" {

trn_status trn_devices(trn_device_list** out) {
    return guarded(__func__, [&] {
        require_pointer(out, "out");
        *out = nullptr;
        auto list = std::make_unique<trn_device_list>();
        for (const auto& family : trn::default_registry().status())
            list->devices.insert(list->devices.end(), family.devices.begin(), family.devices.end());
        *out = list.release();
    });
}

size_t trn_device_count(const trn_device_list* list) { return list ? list->devices.size() : 0; }

trn_status trn_device_get(const trn_device_list* list, size_t index, trn_device_info* out) {
    return guarded(__func__, [&] {
        require_pointer(list, "list");
        require_pointer(out, "out");
        if (index >= list->devices.size())
            throw InvalidArgument("index " + std::to_string(index) + " is out of range (" +
                                  std::to_string(list->devices.size()) + " devices)");
        *out = trn::capi::c_device_info(list->devices[index]);
    });
}

void trn_device_list_destroy(trn_device_list* list) { delete list; }

}  // extern "C"
