// Default options for hdHair's sanitizer build (cmake/Sanitizers.cmake),
// compiled into every target so that any run — ctest, a tool by hand, a
// fuzzer — gets them without environment variables. The sanitizers call these
// hooks at start-up; ASAN_OPTIONS, UBSAN_OPTIONS and LSAN_OPTIONS still win.

extern "C" {

// Stop at the first error, with a stack, so that a test fails where it broke.
// The slow unwinder on malloc: Mesa is built without frame pointers, so the
// fast one stops inside it and LeakSanitizer could not name the library a
// suppression below matches (measured: no slower on hdHair's tests).
const char* __asan_default_options() { return "detect_leaks=1:halt_on_error=1:fast_unwind_on_malloc=0"; }
const char* __ubsan_default_options() { return "print_stacktrace=1:halt_on_error=1"; }

// Third-party leaks only, by library name, never an hdHair frame. Mesa's
// drivers (llvmpipe through EGL or OSMesa) keep allocations alive for the life
// of the process (the LLVM JIT, the shader cache, the screen), and libEGL and
// libglapi hold the vendor library state until exit.
const char* __lsan_default_suppressions() {
  return "leak:swrast_dri.so\n"
         "leak:libgallium\n"
         "leak:libLLVM\n"
         "leak:libEGL_mesa.so\n"
         "leak:libOSMesa.so\n"
         "leak:libglapi.so\n";
}

}
