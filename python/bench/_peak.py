"""Peak memory of one call, as the benchmarks measure it (Linux): reset the
high-water mark to the resident size, call, read the mark."""


def rss_kib(field):
    """``field`` of /proc/self/status in KiB (``VmRSS``, ``VmHWM``)."""
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    raise RuntimeError(f"no {field} in /proc/self/status")


def reset_peak():
    """Resets VmHWM to the current resident size (/proc/self/clear_refs)
    and returns that size in KiB: a call's peak is ``rss_kib("VmHWM")``
    after it minus this."""
    with open("/proc/self/clear_refs", "w") as fh:
        fh.write("5")
    return rss_kib("VmRSS")
