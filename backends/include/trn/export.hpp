#pragma once
// The one export macro of every trnkit library. Libraries are built with hidden visibility
// (-fvisibility=hidden, inlines hidden), so only what a public header declares between
// TRN_API_BEGIN and TRN_API_END (or marks TRN_API) is exported; backend internals, nlohmann,
// OpenCV and Boost instantiations stay inside the library. Includes go before TRN_API_BEGIN.
#if defined(__GNUC__) || defined(__clang__)
#define TRN_API __attribute__((visibility("default")))
#define TRN_API_BEGIN _Pragma("GCC visibility push(default)")
#define TRN_API_END _Pragma("GCC visibility pop")
#else
#define TRN_API
#define TRN_API_BEGIN
#define TRN_API_END
#endif
