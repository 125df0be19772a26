#pragma once
// spdlog, for every file of ours that logs: include this, not <spdlog/spdlog.h>
// (tests/lint/check_includes.py holds every file to it).
//
// spdlog formats each message with fmt::detail::vformat_to<char>, a template
// that fmt 9 defines in its header and does not declare extern. Every file
// that logs would compile fmt's whole formatting engine again: about 4 s of
// -O3 per file. The declaration below has each file call the one copy that
// common/src/spdlog_format.cpp makes (in ubersim_common) instead.
#include <fmt/format.h>

#if FMT_VERSION >= 90000 && FMT_VERSION < 100000 && !defined(FMT_HEADER_ONLY)
#define UBERSIM_FMT_FORMAT_ENGINE_EXTERN 1
FMT_BEGIN_NAMESPACE
namespace detail {
extern template FMT_API void vformat_to<char>(buffer<char>& buffer, basic_string_view<char> format,
                                              basic_format_args<buffer_context<char>> arguments,
                                              locale_ref locale);
}  // namespace detail
FMT_END_NAMESPACE
#endif

#include <spdlog/spdlog.h>
