// Default options for hdHair's sanitizer build (cmake/Sanitizers.cmake),
// compiled into every target so that any run — ctest, a tool by hand, a
// fuzzer — gets them without environment variables. The sanitizers call these
// hooks at start-up; ASAN_OPTIONS, UBSAN_OPTIONS and LSAN_OPTIONS still win.

extern "C" {

// Stop at the first error, with a stack, so that a test fails where it broke.
const char* __asan_default_options() { return "detect_leaks=1:halt_on_error=1"; }
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

// Libraries stay loaded: eglTerminate unloads Mesa's driver, and a leak
// reported at exit from an unloaded library has no module name for the
// suppressions above to match ("<unknown module>"). The slow unwinder would
// name the caller instead, but deadlocks in LLVM's JIT (malloc inside the
// unwinder's own lock). Sanitizer builds only: nothing here ships.
int dlclose(void*) { return 0; }

}
