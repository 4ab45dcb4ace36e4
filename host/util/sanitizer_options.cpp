// sanitizer_options.cpp: runtime defaults of the sanitizer builds (cmake -DMONTECL_SANITIZE=ON,
// -DMONTECL_FUZZ=ON), compiled into montecl, montecl_tests and the fuzz harnesses only, so that a
// plain `ctest` in build-asan, and every montecl subprocess of the CLI tests, runs with them.
// ASAN_OPTIONS / UBSAN_OPTIONS / LSAN_OPTIONS in the environment still override these.
//
// Leak suppressions name third-party libraries only (docs/fuzzing.md): PoCL and the LLVM it
// builds kernels with, Intel's CPU OpenCL runtime, the OpenCL ICD loader and OpenImageIO keep
// process-lifetime allocations (compiler state, plugin registries, thread pools) that they never
// free. A leak whose stack holds only montecl frames is still reported and fails the test.
//
// verify_asan_link_order=0: `oclgrind montecl ...` (the conformance test) preloads Oclgrind's
// runtime before libasan; ASan then still checks montecl's own code.
extern "C" {

__attribute__((visibility("default"), used)) const char* __asan_default_options() {
  return "verify_asan_link_order=0:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=0:check_initialization_order=1";
}

__attribute__((visibility("default"), used)) const char* __ubsan_default_options() {
  return "print_stacktrace=1:halt_on_error=1";
}

// use_tls=0: LeakSanitizer (GCC 12's) crashes in its stop-the-world tracer ("Tracer caught signal
// 11") while scanning the dynamic TLS blocks of the dlopened OpenImageIO module's dependencies;
// pointers held only in thread-local storage are then not seen as roots (montecl keeps none).
// print_suppressions=0: the suppression statistics would add lines to the one-line errors.
__attribute__((visibility("default"), used)) const char* __lsan_default_options() { return "use_tls=0:print_suppressions=0"; }

__attribute__((visibility("default"), used)) const char* __lsan_default_suppressions() {
  return "leak:libpocl.so\n"
         "leak:libpocl-devices\n"
         "leak:libpocl-devices-pthread.so\n"
         "leak:libpocl-devices-basic.so\n"
         "leak:libLLVM\n"
         "leak:libclang-cpp\n"
         "leak:libOpenCL.so\n"
         // Intel's CPU OpenCL runtime (scripts/with_intel_opencl.sh): kernel argument names
         // strdup'ed per program build and never freed.
         "leak:libintelocl.so\n"
         "leak:libcommon_clang.so\n"
         "leak:libhwloc.so\n"
         "leak:libOpenImageIO\n"
         "leak:libOpenImageIO_Util\n"
         "leak:libOpenEXR\n"
         "leak:libIlmThread\n"
         "leak:libtbb\n"
         "leak:libglib-2.0\n"
         "leak:libboost_thread\n"
         // glibc's dynamic-loader and dlerror state, referenced from thread-local storage only
         // (reported because use_tls=0, below):
         "leak:_dl_resize_dtv\n"
         "leak:add_to_global_resize\n"
         "leak:_dlerror_run\n"
         "leak:__vasprintf_internal\n";
}

}  // extern "C"
