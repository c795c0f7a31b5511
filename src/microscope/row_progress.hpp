#pragma once
// Progress of a render whose rows are shared among OpenMP threads: every thread counts its rows, the first
// thread reports (progress callbacks need not be thread-safe).
#include "petroscope/core/progress.hpp"

#include <atomic>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace petroscope::detail {

inline void row_done(const ProgressCallback& progress, std::atomic<int>& rows_done, int total_rows) {
    const int done = ++rows_done;
#ifdef _OPENMP
    const bool reporter = omp_get_thread_num() == 0;
#else
    const bool reporter = true;
#endif
    if (progress && reporter) progress(static_cast<double>(done) / total_rows);
}

}  // namespace petroscope::detail
