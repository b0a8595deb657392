#pragma once
// An undo journal for an HDF5 file rewritten in place (a series streamed frame by frame).
//
// HDF5 updates a file's superblock, group indices and dataset headers in place and in no order
// a crash can rely on, so a process killed while a frame goes out can leave the file unreadable.
// The journal driver (an HDF5 virtual file driver over POSIX pread/pwrite) copies every 4 KiB
// page of the file as it was when opened into `FILE.journal` before the page is first
// overwritten or cut, and removes the journal when the file closes: the close is the commit. A
// journal left behind by a killed writer is "hot": the next open of the file, for reading or
// writing, puts the pages back and cuts the file to its old length, the file as it was after its
// last complete close. Like SQLite's rollback journal, a live writer holds a lock on its journal
// (flock), so a reader tells a hot journal from one in use; a reader that finds a journal in use,
// or cannot write the file, reads through it (the old pages over the new ones) and leaves both
// files alone.
//
// It guards against the writing process dying (SIGKILL, a crash), not against the machine
// losing power: nothing is synced to the disk before the in-place writes.

#include <cstddef>
#include <filesystem>

#include <hdf5.h>

namespace drumlab::h5 {

/// The journal next to `file`: FILE.journal.
std::filesystem::path journal_path(const std::filesystem::path& file);

/// Sets `fapl` to the journal driver (no driver options).
void use_journal_driver(hid_t fapl);

/// What a journal found next to a file came to.
enum class JournalState {
  none,         ///< there is no journal
  rolled_back,  ///< it was hot: the file is as its last complete close left it
  in_use,       ///< a live writer holds it, or the file cannot be written: read through it
};

/// Rolls back a hot journal next to `file`. Throws InputError naming the journal if it
/// cannot be read or the file cannot be restored.
JournalState recover_journal(const std::filesystem::path& file);

namespace journal_testing {
/// Fault injection for tests: `action` runs before the journal driver's n-th write to the disk
/// (0-based, counting journal records and the file's own writes and cuts), in every file the
/// driver opens from now on; n = -1 turns it off.
void before_io(long n, void (*action)());
}  // namespace journal_testing

}  // namespace drumlab::h5
