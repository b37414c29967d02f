#pragma once

// One writer at a time in a workspace's W/lutex/: every command that writes there holds W/lutex/.lock
// (lib/util/file_lock.h) while it works, `lutex run` for the whole run and a single command (lutex restore,
// lutex texture, ...) for itself. A second writer exits with "W is in use by lutex pid N on HOST (started
// T)"; the lock of a killed writer is taken over with a warning. A command whose outputs all lie outside
// W/lutex (--output elsewhere) takes no lock: it cannot collide with a run there.

#include <memory>

#include "colmap_integration/io/workspace.h"
#include "colmap_integration/stages/output_policy.h"
#include "lib/util/file_lock.h"

namespace lutex {

// The lock file of `workspace`: W/lutex/.lock.
std::filesystem::path WorkspaceLockPath(const Workspace& workspace);

// Takes the workspace's lock when one of `paths`' outputs lies inside W/lutex; null otherwise. Throws
// std::runtime_error naming the holder when another process holds it.
std::unique_ptr<ExclusiveFileLock> LockWorkspaceFor(const Workspace& workspace, const InputsAndOutputs& paths);

// What every stage does before its first write, in this order: refuses an output over or inside an input
// (paths.Check()), takes the workspace's lock as above, then removes what killed writers left of the
// outputs (paths.RemoveStaleTemporaries(), safe once no other lutex writes there). Returns the lock.
std::unique_ptr<ExclusiveFileLock> ClaimOutputs(const Workspace& workspace, const InputsAndOutputs& paths);

}  // namespace lutex
