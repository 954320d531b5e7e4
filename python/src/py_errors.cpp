// trn::Error and trn::BackendUnavailable as Python exceptions carrying the library's message.
#include "py_errors.hpp"

#include "trn/error.hpp"

namespace trn::py {

namespace pyb = pybind11;

void register_errors(pyb::module_& m) {
    // Leaked on purpose: the translator may run until the interpreter ends.
    static PyObject* error = nullptr;
    static PyObject* unavailable = nullptr;
    pyb::tuple bases = pyb::make_tuple(pyb::handle(PyExc_ValueError), pyb::handle(PyExc_RuntimeError));
    error = PyErr_NewExceptionWithDoc("trnkit.Error",
                                      "trnkit refused an input or an operation failed; the message names the argument, "
                                      "file or device (a ValueError and a RuntimeError).",
                                      bases.ptr(), nullptr);
    if (!error) throw pyb::error_already_set();
    unavailable = PyErr_NewExceptionWithDoc("trnkit.BackendUnavailable",
                                            "The requested backend is not built or has no such device.", error, nullptr);
    if (!unavailable) throw pyb::error_already_set();
    m.attr("Error") = pyb::handle(error);
    m.attr("BackendUnavailable") = pyb::handle(unavailable);
    pyb::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const BackendUnavailable& e) {
            PyErr_SetString(unavailable, e.what());
        } catch (const Error& e) {
            PyErr_SetString(error, e.what());
        }
    });
}

}  // namespace trn::py
