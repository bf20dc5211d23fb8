/* Thin C layer over the Exodus II C library (Debian libexodusii-dev) for
 * mesh_exodus.f90: ex_open is a macro, and the library's integer arguments
 * are "void_int" (int or int64_t by a run-time option). Every function
 * returns 0 on success and the library's negative code (or -1) on failure;
 * integers are C int (the library's default 32-bit API), reals double. */
#include <string.h>
#include <exodusII.h>

int impact3d_exo_open(const char *path, int *exoid, float *version)
{
  int comp_ws = 8, io_ws = 0;
  ex_opts(0); /* no messages from the library: the caller writes its own */
  *exoid = ex_open(path, EX_READ, &comp_ws, &io_ws, version);
  return *exoid < 0 ? -1 : 0;
}

int impact3d_exo_close(int exoid) { return ex_close(exoid) < 0 ? -1 : 0; }

int impact3d_exo_init(int exoid, int *ndim, int *nnode, int *nelem, int *nblock,
                      int *nnodeset, int *nsideset)
{
  char title[MAX_LINE_LENGTH + 1];
  return ex_get_init(exoid, title, ndim, nnode, nelem, nblock, nnodeset, nsideset) < 0 ? -1 : 0;
}

int impact3d_exo_coord(int exoid, double *x, double *y, double *z)
{
  return ex_get_coord(exoid, x, y, z) < 0 ? -1 : 0;
}

/* kind: 1 element blocks, 3 side sets (ex_entity_type EX_ELEM_BLOCK, EX_SIDE_SET). */
static ex_entity_type entity(int kind) { return kind == 3 ? EX_SIDE_SET : EX_ELEM_BLOCK; }

int impact3d_exo_ids(int exoid, int kind, int *ids)
{
  return ex_get_ids(exoid, entity(kind), ids) < 0 ? -1 : 0;
}

/* The name of block or set id into name[len] (NUL-terminated; "" if none). */
int impact3d_exo_name(int exoid, int kind, int id, char *name, int len)
{
  char buffer[257];
  memset(buffer, 0, sizeof buffer);
  if (ex_set_max_name_length(exoid, 256) < 0) return -1;
  if (ex_get_name(exoid, entity(kind), id, buffer) < 0) return -1;
  strncpy(name, buffer, (size_t)len - 1);
  name[len - 1] = '\0';
  return 0;
}

/* Element block id: its element type (into type[len]), element count and nodes per element. */
int impact3d_exo_block(int exoid, int id, char *type, int len, int *nelem, int *nper)
{
  char buffer[MAX_STR_LENGTH + 1];
  int nedge = 0, nface = 0, nattr = 0;
  memset(buffer, 0, sizeof buffer);
  if (ex_get_block(exoid, EX_ELEM_BLOCK, id, buffer, nelem, nper, &nedge, &nface, &nattr) < 0)
    return -1;
  strncpy(type, buffer, (size_t)len - 1);
  type[len - 1] = '\0';
  return 0;
}

int impact3d_exo_conn(int exoid, int id, int *conn)
{
  return ex_get_conn(exoid, EX_ELEM_BLOCK, id, conn, NULL, NULL) < 0 ? -1 : 0;
}

int impact3d_exo_side_set_size(int exoid, int id, int *nside)
{
  int ndf = 0;
  return ex_get_set_param(exoid, EX_SIDE_SET, id, nside, &ndf) < 0 ? -1 : 0;
}

int impact3d_exo_side_set(int exoid, int id, int *elem, int *side)
{
  return ex_get_set(exoid, EX_SIDE_SET, id, elem, side) < 0 ? -1 : 0;
}

/* Reads by ranges (every rank reads its own part of the file): nodes
 * start..start+n-1 (1-based), elements start..start+n-1 of block id,
 * entries start..start+n-1 of side set id. */
int impact3d_exo_partial_coord(int exoid, int start, int n, double *x, double *y, double *z)
{
  if (n <= 0) return 0;
  return ex_get_partial_coord(exoid, start, n, x, y, z) < 0 ? -1 : 0;
}

int impact3d_exo_partial_conn(int exoid, int id, int start, int n, int *conn)
{
  if (n <= 0) return 0;
  return ex_get_partial_conn(exoid, EX_ELEM_BLOCK, id, start, n, conn, NULL, NULL) < 0 ? -1 : 0;
}

int impact3d_exo_partial_side_set(int exoid, int id, int start, int n, int *elem, int *side)
{
  if (n <= 0) return 0;
  return ex_get_partial_side_set(exoid, id, start, n, elem, side) < 0 ? -1 : 0;
}
