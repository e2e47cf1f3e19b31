// A shared library that exports what libcloth.so must not: a C++ symbol of
// a bundled dependency, and none of the C API. check_library.py's export
// check must fail on it (ctest cloth_library.check_catches_a_leaked_symbol).
namespace tinyobj {
__attribute__((visibility("default"))) int probe_leaked_function(int x) { return x + 1; }
}  // namespace tinyobj
