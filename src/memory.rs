//! Memory of this process and of the machine: the resident set now and at its peak (Linux
//! `/proc/self/status`: `VmRSS`, `VmHWM`), the memory the OS reports available
//! (`MemAvailable` in `/proc/meminfo`), and byte counts as people write them (`8G`, `512M`).
//! Where `/proc` is missing the readings are `None`.

/// A field of `/proc/self/status` in bytes (`VmRSS:  1234 kB`).
fn status_bytes(field: &str) -> Option<u64> {
    let text = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = text.lines().find(|l| l.starts_with(field))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// This process's resident memory now, bytes.
pub fn current_rss_bytes() -> Option<u64> {
    status_bytes("VmRSS:")
}

/// This process's peak resident memory so far (the high-water mark), bytes.
pub fn peak_rss_bytes() -> Option<u64> {
    status_bytes("VmHWM:")
}

/// The bytes this process may still allocate: the least of the memory the OS reports
/// available (`MemAvailable` in `/proc/meminfo`) and what the address-space limit (`ulimit -v`,
/// "Max address space" in `/proc/self/limits`) leaves beside the process's current size
/// (`VmSize`). `None` where `/proc` does not say (then no check is made). Readers check an
/// allocation a file asks for against it before making it, so a corrupt header is refused with
/// a message instead of aborting the process.
pub fn available_bytes() -> Option<u64> {
    match (mem_available(), address_space_left()) {
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

/// Parses a byte count with an optional binary suffix: `512`, `64k`, `800M`, `8G`, `1T`
/// (k = 2¹⁰ … T = 2⁴⁰; a trailing `B` or `iB` is allowed: `8GiB`).
pub fn parse_bytes(s: &str) -> std::result::Result<u64, String> {
    let t = s.trim();
    let t = t.strip_suffix("iB").or_else(|| t.strip_suffix('B')).unwrap_or(t);
    let (digits, shift) = match t.char_indices().last() {
        Some((i, c)) if c.is_ascii_alphabetic() => {
            let shift = match c.to_ascii_uppercase() {
                'K' => 10,
                'M' => 20,
                'G' => 30,
                'T' => 40,
                _ => return Err(format!("unknown size suffix '{c}' in \"{s}\": use k, M, G or T")),
            };
            (&t[..i], shift)
        }
        _ => (t, 0),
    };
    let v: f64 = digits.trim().parse().map_err(|_| format!("expected a size such as 8G or 512M, found \"{s}\""))?;
    let bytes = v * (1u64 << shift) as f64;
    if !(bytes.is_finite() && bytes >= 1.0 && bytes < u64::MAX as f64) {
        return Err(format!("expected a positive size such as 8G or 512M, found \"{s}\""));
    }
    Ok(bytes as u64)
}

/// A byte count for messages: "3.20 GB (3200000000 bytes)".
pub fn human(bytes: u64) -> String {
    let b = bytes as f64;
    let (v, unit) = match b {
        b if b >= 1e12 => (b / 1e12, "TB"),
        b if b >= 1e9 => (b / 1e9, "GB"),
        b if b >= 1e6 => (b / 1e6, "MB"),
        b if b >= 1e3 => (b / 1e3, "kB"),
        _ => return format!("{bytes} bytes"),
    };
    format!("{v:.2} {unit} ({bytes} bytes)")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_binary_suffixes() {
        assert_eq!(parse_bytes("512"), Ok(512));
        assert_eq!(parse_bytes("64k"), Ok(65_536));
        assert_eq!(parse_bytes("1.5M"), Ok(1_572_864));
        assert_eq!(parse_bytes("8G"), Ok(8 << 30));
        assert_eq!(parse_bytes("8GiB"), Ok(8 << 30));
        assert_eq!(parse_bytes("2TB"), Ok(2 << 40));
        for bad in ["", "G", "-1G", "0", "8X", "lots", "nan"] {
            assert!(parse_bytes(bad).is_err(), "{bad:?} accepted");
        }
    }

    #[test]
    fn this_host_reports_available_memory() {
        if std::path::Path::new("/proc/meminfo").exists() {
            assert!(available_bytes().is_some_and(|b| b > 0));
        }
    }

    #[test]
    fn this_process_reports_its_memory() {
        if std::path::Path::new("/proc/self/status").exists() {
            let now = current_rss_bytes().expect("VmRSS");
            let peak = peak_rss_bytes().expect("VmHWM");
            assert!(now > 0 && peak >= now, "{now} {peak}");
        }
    }

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
