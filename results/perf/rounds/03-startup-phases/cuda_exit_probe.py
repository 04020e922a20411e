# Times a process's exit with and without a CUDA context: a child process opens the driver
# (cuInit, primary context, one 64 MiB allocation) or not, writes the clock just before
# os._exit(0), and the parent reads the clock when waitpid returns. CLOCK_MONOTONIC is shared.
import ctypes, os, sys, time

def child(with_cuda, fd):
    try:
        open_driver(with_cuda)
    finally:
        os.write(fd, repr(time.monotonic()).encode())
        os._exit(0)

def open_driver(with_cuda):
    if with_cuda:
        cuda = ctypes.CDLL("libcuda.so.1")
        cuda.cuInit(0)
        dev = ctypes.c_int(); cuda.cuDeviceGet(ctypes.byref(dev), 0)
        ctx = ctypes.c_void_p(); cuda.cuDevicePrimaryCtxRetain(ctypes.byref(ctx), dev)
        cuda.cuCtxSetCurrent(ctx)
        ptr = ctypes.c_uint64(); cuda.cuMemAlloc_v2(ctypes.byref(ptr), ctypes.c_size_t(64 << 20))

for with_cuda in (False, True, False, True, False, True, False, True, False, True):
    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(r); child(with_cuda, w)
    os.close(w)
    os.waitpid(pid, 0)
    t_reaped = time.monotonic()
    t_exit = float(os.read(r, 64).decode()); os.close(r)
    print(f"cuda {int(with_cuda)} exit_to_reaped_ms {1e3 * (t_reaped - t_exit):.1f}")
