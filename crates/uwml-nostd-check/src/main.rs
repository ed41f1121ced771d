//! The no_std link proof: a freestanding x86-64 Linux binary (no C runtime, no libc, no
//! allocator, see build.rs) that calls every evaluation function of uwml-core and exits with the
//! number of unexpected results. That it links at all proves that those functions, in every
//! instantiation used here, need nothing but `core` (and the float routines of `libm`).

#![no_std]
#![no_main]

#[cfg(not(all(target_arch = "x86_64", target_os = "linux")))]
compile_error!("the no_std check binary runs on x86-64 Linux only (raw `exit` system call)");

#[cfg(not(any(feature = "canary-alloc", feature = "canary-libc", feature = "canary-index")))]
mod exercise;

/// Entry point from the kernel: the stack pointer is 16-byte aligned here, where a Rust function
/// expects it 8 bytes off (a return address pushed); so align it and call into Rust.
///
/// # Safety
/// Only the kernel calls it, once, as the process's entry point.
#[unsafe(naked)]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn _start() -> ! {
    core::arch::naked_asm!("xor ebp, ebp", "and rsp, -16", "call {main}", "ud2", main = sym main)
}

extern "C" fn main() -> ! {
    // The canaries that only test the link flags leave out the calls, which take most of the build.
    #[cfg(not(any(feature = "canary-alloc", feature = "canary-libc", feature = "canary-index")))]
    let bad = exercise::exercise();
    #[cfg(any(feature = "canary-alloc", feature = "canary-libc", feature = "canary-index"))]
    let bad = 0;
    #[cfg(feature = "canary-index")]
    let bad = bad + u32::from([1u8, 2, 3][core::hint::black_box(5)]);
    #[cfg(feature = "canary-alloc")]
    let bad = bad + canary_alloc();
    #[cfg(feature = "canary-libc")]
    let bad = bad + canary_libc();
    exit(bad.min(255) as i32)
}

/// Must fail to link: an allocation needs a global allocator, which nothing here provides.
#[cfg(feature = "canary-alloc")]
fn canary_alloc() -> u32 {
    extern crate alloc;
    let v = alloc::vec::Vec::<u8>::with_capacity(core::hint::black_box(64));
    v.capacity() as u32 & 0
}

/// Must fail to link: `getpid` is libc's, which is not linked.
#[cfg(feature = "canary-libc")]
fn canary_libc() -> u32 {
    unsafe extern "C" {
        fn getpid() -> i32;
    }
    // SAFETY: never runs; the binary does not link.
    u32::from(unsafe { getpid() } < 0)
}

/// The `exit_group` system call: ends the process with `code`.
fn exit(code: i32) -> ! {
    // SAFETY: exit_group (231) takes one integer argument and never returns.
    unsafe { core::arch::asm!("syscall", in("rax") 231, in("rdi") code, options(noreturn, nostack)) }
}

// With uwml-core's `std` feature, std (and its panic handler) comes in through nalgebra.
#[cfg(not(feature = "canary-std"))]
#[panic_handler]
#[inline(never)]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    // SAFETY: `ud2` raises SIGILL, which ends the process (exit status 132 in a shell).
    unsafe { core::arch::asm!("ud2", options(noreturn, nostack)) }
}

// The four memory routines the compiler may call, which libc would otherwise provide. Volatile
// accesses keep LLVM from recognizing the loops as memcpy/memset and calling them from themselves.

/// # Safety
/// As C's `memcpy`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn memcpy(dest: *mut u8, src: *const u8, n: usize) -> *mut u8 {
    for i in 0..n {
        // SAFETY: the caller guarantees `n` valid bytes at both pointers.
        unsafe { dest.add(i).write_volatile(src.add(i).read_volatile()) };
    }
    dest
}

/// # Safety
/// As C's `memmove`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn memmove(dest: *mut u8, src: *const u8, n: usize) -> *mut u8 {
    if (dest as usize) <= (src as usize) {
        for i in 0..n {
            // SAFETY: as memcpy; forwards, so an overlapping source is read before it is written.
            unsafe { dest.add(i).write_volatile(src.add(i).read_volatile()) };
        }
    } else {
        for i in (0..n).rev() {
            // SAFETY: as memcpy; backwards, for the same reason.
            unsafe { dest.add(i).write_volatile(src.add(i).read_volatile()) };
        }
    }
    dest
}

/// # Safety
/// As C's `memset`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn memset(dest: *mut u8, value: i32, n: usize) -> *mut u8 {
    for i in 0..n {
        // SAFETY: the caller guarantees `n` valid bytes at `dest`.
        unsafe { dest.add(i).write_volatile(value as u8) };
    }
    dest
}

/// # Safety
/// As C's `memcmp`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn memcmp(a: *const u8, b: *const u8, n: usize) -> i32 {
    for i in 0..n {
        // SAFETY: the caller guarantees `n` valid bytes at both pointers.
        let (x, y) = unsafe { (a.add(i).read_volatile(), b.add(i).read_volatile()) };
        if x != y {
            return i32::from(x) - i32::from(y);
        }
    }
    0
}

/// # Safety
/// As `memcmp`, whose result it is (only its being zero or not matters).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bcmp(a: *const u8, b: *const u8, n: usize) -> i32 {
    // SAFETY: same contract.
    unsafe { memcmp(a, b, n) }
}
