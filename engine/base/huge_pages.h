#pragma once
// A hint that makes large buffers cheap to fill: huge pages instead of one page fault per 4 KB.
#include <cstddef>

namespace mostyle {

// Asks the kernel to back the whole pages inside [data, data + bytes) with transparent huge
// pages (Linux madvise MADV_HUGEPAGE), before the buffer is first written. Filling a 20 MB
// buffer then takes about ten page faults instead of five thousand, which in a virtual machine
// is most of the cost of loading a large file (tests/bench/bvh_bench). Only a hint: it does
// nothing for buffers under 2 MB, on other systems, or when the kernel says no; it never fails
// and never changes the buffer's contents. O(1).
void advise_huge_pages(void* data, size_t bytes);

}  // namespace mostyle
