"""The machine a validation ran on, for the reports' headers: the CPU model and how many
logical CPUs (from /proc/cpuinfo), else what the platform module says."""
import platform


def machine():
    model, count = None, 0
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name") and model is None:
                    model = line.split(":", 1)[1].strip()
                if line.startswith("processor"):
                    count += 1
    except OSError:
        pass
    model = model or platform.processor() or "an unknown CPU"
    return f"{model}, {count} logical CPUs" if count else model
