/* The C library's allocation policy during the set-up (glibc only).
 *
 * glibc's malloc serves requests above its mmap threshold (128 kB at start)
 * with mmap, and raises the threshold to the size of any mmapped block that
 * is freed, up to 32 MB (mallopt(3), M_MMAP_THRESHOLD). An imported mesh's
 * reader frees temporaries of a few MB; the threshold then rises past them,
 * and the partition's and the migration's later arrays come from the heap,
 * where they fragment it: the whole run's peak memory rose by about 20%
 * (docs/scaling.md, section 4). So the set-up runs with the threshold
 * pinned at 128 kB (mallopt turns the adjustment off).
 *
 * The time loop must not: its large temporaries would then be mapped and
 * unmapped every cycle (35% more CPU time on the 1-rank Sedov 30^3, most of
 * it in the kernel). After the set-up the threshold goes to 32 MB, glibc's
 * ceiling for the adjustment, and the trim threshold to twice that, as the
 * adjustment would set them: blocks below 32 MB come from the heap and stay
 * there for reuse, as they do by default once a large block has been freed.
 *
 * A threshold the user set in the environment (MALLOC_MMAP_THRESHOLD_, or
 * glibc.malloc.mmap_threshold in GLIBC_TUNABLES; glibc reads them at the
 * first malloc) is left alone, set-up and loop; so is a trim threshold
 * (MALLOC_TRIM_THRESHOLD_, glibc.malloc.trim_threshold). Where mallopt is absent
 * (another C library: CMake's check leaves IMPACT3D_HAVE_MALLOPT
 * undefined), nothing is done. Bound to Fortran by module core_malloc. No
 * MPI here. */
#include <stdlib.h>
#include <string.h>
#ifdef IMPACT3D_HAVE_MALLOPT
#include <malloc.h>
#endif

/* 1 if this process pinned the threshold (and may release it). */
static int pinned = 0;

/* 1 if the environment sets the parameter: variable (MALLOC_..._) or
 * tunable (glibc.malloc....) in GLIBC_TUNABLES. */
static int environment_sets(const char *variable, const char *tunable)
{
  const char *tunables = getenv("GLIBC_TUNABLES");
  if (getenv(variable) != NULL) return 1;
  return tunables != NULL && strstr(tunables, tunable) != NULL;
}

/* The set-up's policy: the mmap threshold fixed at bytes. Returns 1 if set,
 * 0 if the environment sets the threshold (left alone), -1 if this C
 * library has no mallopt or refused the value. */
int impact3d_malloc_setup(long bytes)
{
  if (environment_sets("MALLOC_MMAP_THRESHOLD_", "glibc.malloc.mmap_threshold")) return 0;
#if defined(IMPACT3D_HAVE_MALLOPT) && defined(M_MMAP_THRESHOLD)
  if (bytes < 0 || bytes > 0x7fffffffL) return -1;
  if (mallopt(M_MMAP_THRESHOLD, (int)bytes) != 1) return -1;
  pinned = 1;
  return 1;
#else
  (void)bytes;
  return -1;
#endif
}

/* The time loop's policy, after impact3d_malloc_setup: the mmap threshold
 * at mmap_bytes and the trim threshold at trim_bytes. Returns 1 if set, 0
 * if the set-up's policy was not applied (nothing to undo), -1 if refused. */
int impact3d_malloc_loop(long mmap_bytes, long trim_bytes)
{
  if (!pinned) return 0;
#if defined(IMPACT3D_HAVE_MALLOPT) && defined(M_MMAP_THRESHOLD) && defined(M_TRIM_THRESHOLD)
  if (mmap_bytes < 0 || mmap_bytes > 0x7fffffffL) return -1;
  if (trim_bytes < 0 || trim_bytes > 0x7fffffffL) return -1;
  if (mallopt(M_MMAP_THRESHOLD, (int)mmap_bytes) != 1) return -1;
  if (!environment_sets("MALLOC_TRIM_THRESHOLD_", "glibc.malloc.trim_threshold") &&
      mallopt(M_TRIM_THRESHOLD, (int)trim_bytes) != 1) return -1;
  pinned = 0;
  return 1;
#else
  (void)mmap_bytes;
  (void)trim_bytes;
  return -1;
#endif
}
