// The one instantiation of fmt's formatting engine that spdlog calls, made
// here once for every file that logs (ubersim/spdlog.hpp declares it extern and
// says why). libfmt's shared library holds it too, made by the compiler that
// built libfmt; this copy has the mangled name of the compiler that builds
// ubersim (GCC and clang name it differently), and the linker keeps one.
#include "ubersim/spdlog.hpp"

#ifdef UBERSIM_FMT_FORMAT_ENGINE_EXTERN
FMT_BEGIN_NAMESPACE
namespace detail {
template FMT_API void vformat_to<char>(buffer<char>& buffer, basic_string_view<char> format,
                                       basic_format_args<buffer_context<char>> arguments,
                                       locale_ref locale);
}  // namespace detail
FMT_END_NAMESPACE
#endif
