//! What happens when something goes wrong on some ranks.
//!
//! - **An error one rank finds** (its copy of a referenced file is missing, its maps would not
//!   fit in its memory): every such check ends in [`agree`], a collective step where all ranks
//!   learn every rank's outcome. If any failed, all return the first failure's error (naming its
//!   rank and host), rank 0 prints it, and every rank finalises MPI and exits with its code — no
//!   rank is left waiting in a collective.
//! - **A rank that dies** (killed, out of memory, its node lost): MPI's default error handler
//!   (`MPI_ERRORS_ARE_FATAL`) and `mpirun` end the whole job, and `mpirun` names the rank, its
//!   PID and host and the signal. Rank 0 writes outputs only after the eye pass has received
//!   every rank's rows and the final per-rank reports, all to temporary files renamed into place
//!   last ([`crate::output::write_outputs`]); a rank that dies before then leaves no output.
//!   (If rank 0 itself is killed while renaming, hidden `.NAME.PID.N.tmp` files may remain.)
//! - **A broken protocol invariant** (a bug): [`super::Comm::abort`] ends every rank.
//!
//! `scripts/test_mpi.sh` kills a rank with `SIGKILL` during the photon pass and during the eye
//! pass and checks that `mpirun` fails and the output directory stays empty.

use super::Comm;
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// One rank's outcome, as the other ranks see it.
#[derive(Serialize, Deserialize)]
struct Outcome {
    host: String,
    /// `None` for success; else the exit code and message.
    failure: Option<(i32, String)>,
}

/// Makes an outcome collective: `Ok` on every rank if every rank's `local` is `Ok`, else the
/// first failing rank's error on every rank. The failing rank returns its own error unchanged;
/// the others get its message prefixed by its rank and host, with its exit code. Collective.
pub fn agree<T>(comm: &Comm, local: Result<T>) -> Result<T> {
    let mine = Outcome { host: comm.host(), failure: local.as_ref().err().map(|e| (e.exit_code(), e.to_string())) };
    let all = comm.all_gather_json(&mine);
    match first_failure(&all) {
        None => local,
        Some(r) if r == comm.rank() => local,
        Some(r) => {
            let (code, message) = all[r].failure.clone().unwrap_or((1, String::new()));
            Err(remote_error(r, comm.size(), &all[r].host, code, &message))
        }
    }
}

fn first_failure(all: &[Outcome]) -> Option<usize> {
    all.iter().position(|o| o.failure.is_some())
}

/// Another rank's error as this rank reports it: same exit code, message naming the rank.
pub fn remote_error(rank: usize, size: usize, host: &str, code: i32, message: &str) -> Error {
    let message = format!("rank {rank} of {size} (host {host}): {message}");
    match code {
        2 => Error::input(None, message),
        _ => Error::internal(message),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_local_world_keeps_its_own_outcome() {
        let w = Comm::local();
        assert_eq!(agree(&w, Ok(5)).ok(), Some(5));
        let e = agree::<()>(&w, Err(Error::input(None, "bad"))).unwrap_err();
        assert_eq!((e.exit_code(), e.to_string()), (2, "bad".to_string()));
    }

    #[test]
    fn the_first_failure_wins_and_keeps_its_exit_code() {
        let ok = || Outcome { host: "a".into(), failure: None };
        let fail = |c: i32| Outcome { host: "b".into(), failure: Some((c, "m".into())) };
        assert_eq!(first_failure(&[ok(), ok()]), None);
        assert_eq!(first_failure(&[ok(), fail(2), fail(1)]), Some(1));
        let e = remote_error(1, 3, "b", 2, "x.ies: cannot read");
        assert_eq!(e.exit_code(), 2);
        assert_eq!(e.to_string(), "rank 1 of 3 (host b): x.ies: cannot read");
        assert_eq!(remote_error(2, 3, "c", 1, "boom").exit_code(), 1);
    }
}
