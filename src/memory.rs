//! The memory budget of the particle maps and guide caches (`[maps] max_memory`,
//! `--max-memory`): how a size is written (`512M`, `4G`, `1.5GiB`, or bytes) and how much
//! memory the machine has, from which the default budget comes.

/// A size in bytes from text: a number with an optional unit `K`, `M`, `G` or `T` (powers
/// of 1024; `KiB`, `KB` and lower case are the same), e.g. `512M`, `1.5G`, `8589934592`.
pub fn parse_size(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let x: f64 = number
        .parse()
        .map_err(|_| format!("expects a size such as 512M or 4G, got '{t}'"))?;
    let shift = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 0,
        "k" | "kb" | "kib" => 10,
        "m" | "mb" | "mib" => 20,
        "g" | "gb" | "gib" => 30,
        "t" | "tb" | "tib" => 40,
        u => return Err(format!("has an unknown unit '{u}' in '{t}' (K, M, G or T)")),
    };
    let bytes = x * (1u64 << shift) as f64;
    if !(bytes.is_finite() && bytes >= 1.0 && bytes < 2f64.powi(63)) {
        return Err(format!("must be between 1 byte and 8 EiB, got '{t}'"));
    }
    Ok(bytes as u64)
}

/// A size as [`parse_size`] reads it back, in the largest unit that shows it within 0.1%
/// (`512M`, `1.5G`).
pub fn format_size(bytes: u64) -> String {
    for (shift, unit) in [(40, "T"), (30, "G"), (20, "M"), (10, "K")] {
        let x = bytes as f64 / (1u64 << shift) as f64;
        if x >= 1.0 {
            let rounded = (x * 1000.0).round() / 1000.0;
            return format!("{rounded}{unit}");
        }
    }
    bytes.to_string()
}

/// The machine's memory in bytes: the physical memory (`/proc/meminfo`'s `MemTotal`) or the
/// control group's limit (`/sys/fs/cgroup/memory.max`, cgroup v2), whichever is smaller;
/// `None` where neither can be read (not Linux).
pub fn machine_memory() -> Option<u64> {
    let total = std::fs::read_to_string("/proc/meminfo").ok().and_then(|s| {
        let line = s.lines().find(|l| l.starts_with("MemTotal:"))?;
        let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
        Some(kib * 1024)
    });
    let limit = std::fs::read_to_string("/sys/fs/cgroup/memory.max")
        .ok()
        .and_then(|s| s.trim().parse::<u64>().ok());
    match (total, limit) {
        (Some(t), Some(l)) => Some(t.min(l)),
        (t, l) => t.or(l),
    }
}

/// The share of the machine's memory the maps and caches may take when no budget is set.
pub const DEFAULT_SHARE: f64 = 0.5;

/// The budget where none is set and the machine's memory cannot be read.
pub const FALLBACK_BUDGET: u64 = 4 << 30;

/// The budget of the maps and caches: `max_memory` when set, else [`DEFAULT_SHARE`] of
/// [`machine_memory`] (else [`FALLBACK_BUDGET`]).
pub fn budget(max_memory: Option<u64>) -> u64 {
    max_memory.unwrap_or_else(|| {
        machine_memory().map_or(FALLBACK_BUDGET, |m| (m as f64 * DEFAULT_SHARE) as u64)
    })
}

/// Serde form of an optional size (`[maps] max_memory = "4G"`, or a number of bytes).
pub mod serde_size {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(size: &Option<u64>, s: S) -> Result<S::Ok, S::Error> {
        match size {
            Some(b) => s.serialize_str(&super::format_size(*b)),
            None => s.serialize_none(),
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<u64>, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Size {
            Bytes(u64),
            Text(String),
        }
        match Size::deserialize(d)? {
            Size::Bytes(0) => Err(serde::de::Error::custom("must be at least 1 byte")),
            Size::Bytes(b) => Ok(Some(b)),
            Size::Text(t) if t == "auto" => Ok(None),
            Size::Text(t) => super::parse_size(&t)
                .map(Some)
                .map_err(serde::de::Error::custom),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_with_their_units() {
        assert_eq!(parse_size("512M"), Ok(512 << 20));
        assert_eq!(parse_size("1.5G"), Ok(3 << 29));
        assert_eq!(parse_size("4 GiB"), Ok(4 << 30));
        assert_eq!(parse_size("2k"), Ok(2048));
        assert_eq!(parse_size("1000"), Ok(1000));
        for bad in ["", "G", "-1G", "0", "1X", "1e400", "nan"] {
            assert!(parse_size(bad).is_err(), "{bad} accepted");
        }
        for n in [1000, 512 << 20, 3 << 29, 4 << 30, 5 << 40] {
            assert_eq!(parse_size(&format_size(n)), Ok(n), "{}", format_size(n));
        }
    }

    #[test]
    fn the_machine_has_memory() {
        // Linux, as CI: MemTotal is readable and the default budget is half of it.
        if cfg!(target_os = "linux") {
            let m = machine_memory().expect("/proc/meminfo");
            assert!(m > 1 << 28, "{m} bytes");
            assert_eq!(budget(None), (m as f64 * DEFAULT_SHARE) as u64);
        }
        assert_eq!(budget(Some(123)), 123);
    }
}
