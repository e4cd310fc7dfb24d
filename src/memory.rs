//! How much memory this process may still allocate: the least of the memory the OS reports
//! available (`MemAvailable` in `/proc/meminfo`) and what the address-space limit (`ulimit -v`,
//! "Max address space" in `/proc/self/limits`) leaves beside the process's current size
//! (`VmSize` in `/proc/self/status`). Readers check an allocation a file asks for against it
//! before making it, so a corrupt header is refused with a message instead of aborting the
//! process.

/// The bytes this process may still allocate, or `None` where `/proc` does not say (then no
/// check is made).
pub fn available_bytes() -> Option<u64> {
    let os = mem_available();
    let limit = address_space_left();
    match (os, limit) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// `MemAvailable` from `/proc/meminfo`, in bytes.
pub fn mem_available() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    kib_field(&text, "MemAvailable:")
}

/// The address-space limit minus the current virtual size, bytes (`None` when unlimited).
fn address_space_left() -> Option<u64> {
    let limits = std::fs::read_to_string("/proc/self/limits").ok()?;
    let line = limits.lines().find(|l| l.starts_with("Max address space"))?;
    let soft: u64 = line["Max address space".len()..].split_whitespace().next()?.parse().ok()?;
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let size = kib_field(&status, "VmSize:")?;
    Some(soft.saturating_sub(size))
}

/// A `Name:   1234 kB` field, in bytes.
fn kib_field(text: &str, name: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(name))?;
    let kib: u64 = line[name.len()..].split_whitespace().next()?.parse().ok()?;
    Some(kib * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kib_fields_are_read_in_bytes() {
        assert_eq!(kib_field("MemTotal: 10 kB\nMemAvailable:    2048 kB\n", "MemAvailable:"), Some(2048 * 1024));
        assert_eq!(kib_field("MemTotal: 10 kB\n", "MemAvailable:"), None);
    }

    #[test]
    fn this_process_may_allocate_something_but_not_more_than_the_machine_has() {
        if let (Some(avail), Some(os)) = (available_bytes(), mem_available()) {
            assert!(avail > 0 && avail <= os, "{avail} of {os}");
        }
    }
}
