// A loop whose steps are decided in order but computed ahead on several threads (`continue
// --all`: each locked state is followed unless a branch followed before it already passes
// through it). Its result is the sequential loop's, bit for bit.
#pragma once

#include <functional>

namespace metrosync {

// The loop
//   for (k = 0; k < count; ++k) if (!skip(k)) { compute(k); commit(k); }
// with compute(k) run ahead on up to `jobs` threads (0: one per hardware thread). skip and
// commit run one at a time, commit in order of k; skip(k) may also be asked early and more than
// once, so it must only read, and once true stay true (commits only add to what it looks at).
// compute(k) must not depend on commits: it may run for a k that turns out skipped, and its work
// is then dropped. An exception of compute(k) is rethrown when k's turn to be committed comes
// (never for a skipped k); one of commit stops the loop and is rethrown.
void orderedTasks(long count, int jobs, const std::function<bool(long)>& skip,
                  const std::function<void(long)>& compute,
                  const std::function<void(long)>& commit);

}  // namespace metrosync
