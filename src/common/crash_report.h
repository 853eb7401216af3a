// A process that dies of a fatal signal (an abort inside a Vulkan driver's shader compiler, a segmentation
// fault) first prints the signal, the dying thread and its call stack to stderr: function names where the
// binary exports them (-rdynamic), else addresses relative to the binary for addr2line. The signal's default
// action follows: the process still dies of it. The workbench and every test executable install it.
#pragma once

namespace wb {

// Installs the report for SIGABRT, and unless built with AddressSanitizer (which reports them itself) for
// SIGSEGV, SIGBUS, SIGFPE and SIGILL. `program` (a string that lives as long as the process) heads the
// report.
void installCrashReport(const char* program);

}  // namespace wb
