// tinygltf's implementation compiled into the fuzzer, so its parser is instrumented and
// sanitized too: the executable's definitions take precedence over Debian's libtinygltf.so,
// whose build carries neither coverage counters nor ASan/UBSan checks. Same header, same
// version (2.7.0). Image decoding stays out: the loader installs its own image callback.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>
