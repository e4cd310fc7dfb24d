//! The eye pass across ranks: rank 0 hands out leases of rows ([`super::tiles`]) and collects
//! the finished rows into the image, in pixel order.
//!
//! # Protocol
//! A worker (rank ≠ 0) sends a [`Tag::Request`] carrying the rows of its previous lease (none
//! the first time) and waits for a [`Tag::Lease`]: the next rows, or none, after which it stops.
//! Rank 0 renders leases too, taken from the same [`Dispenser`] on its own thread, while a second
//! thread serves the workers: it polls for requests (`MPI_Improbe` every [`POLL`]; a blocking
//! receive would spin a core), copies their rows into the image and replies. A worker's wait per
//! lease is one round trip; the per-rank report records it (`wait_seconds`).
//!
//! Messages: a request is `[has_rows, first_row, end_row]` as u64 little-endian, then the rows'
//! band values as f32 little-endian; a lease is `[has_rows, first_row, end_row]`.

use super::Comm;
use super::comm::Tag;
use super::tiles::{Dispenser, Schedule, max_rows_for};
use crate::raypath::RayCounts;
use serde::{Deserialize, Serialize};
use std::ops::Range;
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// How often a waiting rank looks for a message.
pub const POLL: Duration = Duration::from_micros(200);

/// Renders rows `range` of the image: their band values (row-major) and the rays traced.
pub type RenderRows<'a> = dyn Fn(Range<usize>) -> (Vec<f32>, RayCounts) + Sync + 'a;

/// What one rank did in the eye pass.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct EyeWork {
    /// Leases this rank rendered.
    pub leases: u64,
    /// Rows this rank rendered.
    pub rows: u64,
    /// Rendering its leases.
    pub compute_seconds: f64,
    /// Waiting for a lease (workers: sending rows and waiting for the reply).
    pub wait_seconds: f64,
    /// Bytes of tile messages this rank sent.
    pub sent_bytes: u64,
    /// Bytes of tile messages this rank received.
    pub received_bytes: u64,
    /// Rays this rank traced in the eye pass, by kind.
    pub rays: RayCounts,
}

/// The eye pass's result on one rank.
pub struct EyeOut {
    /// The image's band values in pixel order (rank 0 only).
    pub data: Option<Vec<f32>>,
    /// What this rank did.
    pub work: EyeWork,
}

/// Runs the eye pass over `rows` rows of `row_values` values each. Collective (point to point).
/// `on_remote_rows` is called on rank 0 as rows arrive from other ranks.
pub fn run(
    comm: &Comm,
    schedule: Schedule,
    rows: usize,
    row_values: usize,
    render: &RenderRows,
    on_remote_rows: &(dyn Fn(u64) + Sync),
) -> EyeOut {
    let max_rows = max_rows_for(row_values * 4);
    if comm.is_root() {
        let dispenser = Mutex::new(Dispenser::new(schedule, rows, comm.size(), max_rows));
        root(comm, &dispenser, rows, row_values, render, on_remote_rows)
    } else {
        EyeOut { data: None, work: worker(comm, render) }
    }
}

fn root(
    comm: &Comm,
    dispenser: &Mutex<Dispenser>,
    rows: usize,
    row_values: usize,
    render: &RenderRows,
    on_remote_rows: &(dyn Fn(u64) + Sync),
) -> EyeOut {
    let image = Mutex::new(vec![0f32; rows * row_values]);
    let mut work = EyeWork::default();
    let served = std::thread::scope(|s| {
        let server = (comm.size() > 1).then(|| s.spawn(|| serve(comm, dispenser, &image, row_values, on_remote_rows)));
        loop {
            // A statement of its own, so the dispenser is unlocked while the lease renders.
            let next = lock(dispenser).next(0);
            let Some(lease) = next else { break };
            let t = Instant::now();
            let (data, rays) = render(lease.clone());
            work.compute_seconds += t.elapsed().as_secs_f64();
            place(comm, &image, row_values, &lease, &data);
            work.leases += 1;
            work.rows += lease.len() as u64;
            work.rays.add(&rays);
        }
        server.map(|h| h.join().unwrap_or_else(|_| comm.abort("the lease server thread panicked")))
    });
    if let Some((sent, received)) = served {
        work.sent_bytes = sent;
        work.received_bytes = received;
    }
    EyeOut { data: Some(image.into_inner().unwrap_or_else(|e| e.into_inner())), work }
}

/// Rank 0's server: answers workers until each has been told there is nothing left. Returns the
/// bytes sent and received.
fn serve(
    comm: &Comm,
    dispenser: &Mutex<Dispenser>,
    image: &Mutex<Vec<f32>>,
    row_values: usize,
    on_remote_rows: &(dyn Fn(u64) + Sync),
) -> (u64, u64) {
    let mut active = comm.size() - 1;
    let (mut sent, mut received) = (0u64, 0u64);
    while active > 0 {
        let Some((from, bytes)) = comm.try_receive(None, Tag::Request) else {
            std::thread::sleep(POLL);
            continue;
        };
        received += bytes.len() as u64;
        let (done, data) = decode(comm, &bytes);
        if let Some(rows) = done {
            place(comm, image, row_values, &rows, &data);
            on_remote_rows(rows.len() as u64);
        }
        let next = lock(dispenser).next(from);
        let reply = encode(next.as_ref(), &[]);
        comm.send(from, Tag::Lease, &reply);
        sent += reply.len() as u64;
        if next.is_none() {
            active -= 1;
        }
    }
    (sent, received)
}

fn worker(comm: &Comm, render: &RenderRows) -> EyeWork {
    let mut work = EyeWork::default();
    let mut done: Option<(Range<usize>, Vec<f32>)> = None;
    loop {
        let t = Instant::now();
        let request = match &done {
            Some((rows, data)) => encode(Some(rows), data),
            None => encode(None, &[]),
        };
        comm.send(0, Tag::Request, &request);
        work.sent_bytes += request.len() as u64;
        drop(request);
        let reply = wait(comm, 0, Tag::Lease);
        work.received_bytes += reply.len() as u64;
        work.wait_seconds += t.elapsed().as_secs_f64();
        let Some(lease) = decode(comm, &reply).0 else { return work };
        let t = Instant::now();
        let (data, rays) = render(lease.clone());
        work.compute_seconds += t.elapsed().as_secs_f64();
        work.leases += 1;
        work.rows += lease.len() as u64;
        work.rays.add(&rays);
        done = Some((lease, data));
    }
}

/// Waits (polling, so as not to spin a core) for a message from `from`.
fn wait(comm: &Comm, from: usize, tag: Tag) -> Vec<u8> {
    loop {
        if let Some((_, bytes)) = comm.try_receive(Some(from), tag) {
            return bytes;
        }
        std::thread::sleep(POLL);
    }
}

fn place(comm: &Comm, image: &Mutex<Vec<f32>>, row_values: usize, rows: &Range<usize>, data: &[f32]) {
    let mut img = lock(image);
    let dst = img.get_mut(rows.start * row_values..rows.end * row_values);
    match dst {
        Some(d) if d.len() == data.len() => d.copy_from_slice(data),
        _ => comm.abort(&format!("rows {rows:?} arrived with {} values", data.len())),
    }
}

/// A message: `[has_rows, first, end]` (u64 LE), then `data` (f32 LE).
pub fn encode(rows: Option<&Range<usize>>, data: &[f32]) -> Vec<u8> {
    let (has, a, b) = rows.map_or((0u64, 0u64, 0u64), |r| (1, r.start as u64, r.end as u64));
    let mut out = Vec::with_capacity(24 + 4 * data.len());
    for v in [has, a, b] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    for v in data {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}

/// Inverse of [`encode`]; a malformed message (a bug) aborts the job.
pub fn decode(comm: &Comm, bytes: &[u8]) -> (Option<Range<usize>>, Vec<f32>) {
    match try_decode(bytes) {
        Some(m) => m,
        None => comm.abort(&format!("malformed eye-pass message of {} bytes", bytes.len())),
    }
}

fn try_decode(bytes: &[u8]) -> Option<(Option<Range<usize>>, Vec<f32>)> {
    let word = |i: usize| bytes.get(8 * i..8 * i + 8).and_then(|b| b.try_into().ok()).map(u64::from_le_bytes);
    let (has, a, b) = (word(0)?, word(1)? as usize, word(2)? as usize);
    let rest = bytes.get(24..)?;
    if rest.len() % 4 != 0 || has > 1 || a > b {
        return None;
    }
    let data = rest.chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    Some(((has == 1).then_some(a..b), data))
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_round_trip() {
        let data = [1.5f32, -0.0, f32::MAX, 3.25e-20];
        let (rows, back) = try_decode(&encode(Some(&(3..9)), &data)).unwrap();
        assert_eq!(rows, Some(3..9));
        assert_eq!(
            back.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            data.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
        );
        assert_eq!(try_decode(&encode(None, &[])), Some((None, vec![])));
        assert_eq!(try_decode(&[0; 23]), None);
        assert_eq!(try_decode(&encode(Some(&(0..1)), &[]).iter().chain(&[1u8]).copied().collect::<Vec<_>>()), None);
    }

    #[test]
    fn a_local_world_renders_every_row_once_in_pixel_order() {
        // Each row's values name the row, so misplaced or repeated rows show.
        let rows = 37;
        let width = 3;
        let calls = Mutex::new(vec![0u32; rows]);
        let render = |r: Range<usize>| {
            let mut c = lock(&calls);
            let data: Vec<f32> = r.clone().flat_map(|y| (0..width).map(move |x| (y * 10 + x) as f32)).collect();
            for y in r {
                c[y] += 1;
            }
            (data, RayCounts { eye: 1, ..Default::default() })
        };
        for schedule in [Schedule::Dynamic, Schedule::Static] {
            lock(&calls).iter_mut().for_each(|c| *c = 0);
            let out = run(&Comm::local(), schedule, rows, width, &render, &|_| {});
            let data = out.data.unwrap();
            let expected: Vec<f32> = (0..rows).flat_map(|y| (0..width).map(move |x| (y * 10 + x) as f32)).collect();
            assert_eq!(data, expected);
            assert!(lock(&calls).iter().all(|&c| c == 1));
            assert_eq!(out.work.rows, rows as u64);
            assert_eq!(out.work.rays.eye, out.work.leases);
        }
    }
}
