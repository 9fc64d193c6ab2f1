#ifndef cbc3d_ThreadWaits_h
#define cbc3d_ThreadWaits_h

/// The spin count the mesher's OpenMP threads get: about 40 microseconds of spinning before an
/// idle thread sleeps, where libgomp's default is 300,000 rounds (milliseconds).
constexpr const char* ShortSpinCount = "1000";

/// Sets GOMP_SPINCOUNT=ShortSpinCount for the programs this process starts, unless the user
/// chose how OpenMP threads wait (OMP_WAIT_POLICY or GOMP_SPINCOUNT set, to anything). Returns
/// whether it set it.
///
/// Why: an idle libgomp thread spins for milliseconds before it sleeps, and between the many
/// short parallel regions of a run it never sleeps. Where other work keeps cores busy, the
/// spinning threads take their turns from the threads doing the work. With one of two cores
/// busy, the brain on 2 threads took 1.34-1.72 s with libgomp's default against 1.06 s with this
/// count (1.0 s on 1 thread); with both cores busy, the nidus took 2.2-3.8 s against 0.7 s. On
/// an idle machine the two are the same within the noise. libgomp reads the variable only when
/// a process starts, so the launcher sets it for the mesher.
bool ShortenThreadWaits();

#endif
