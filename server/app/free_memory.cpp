#include <rrlab/server/app/free_memory.hpp>

#include <cstdlib>  // defines __GLIBC__ (through <features.h>) where glibc is the C library

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace rrlab::server {

void release_free_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);  // every arena, not only the main one (glibc >= 2.8)
#endif
}

}  // namespace rrlab::server
