/* Write a box [0, lx] x [0, ly] x [0, lz] of nx x ny x nz HEX8 elements as
 * an Exodus II file, with the Exodus II C library (Debian libexodusii-dev),
 * for tests that need an imported mesh of a size chosen at test time.
 *
 * Usage: exodus_box NX NY NZ LX LY LZ OUT.exo
 *
 * Nodes and elements are numbered i fastest, then j, then k (the numbering
 * of impact3d's box generator); one element block (id 1) named 'all'; six
 * side sets (ids 1..6) named xmin, xmax, ymin, ymax, zmin, zmax, their
 * entries in element order. Exodus HEX8 sides: 1 = nodes 1-2-6-5 (y = j),
 * 2 = 2-3-7-6 (x = i + 1), 3 = 3-4-8-7 (y = j + 1), 4 = 1-5-8-4 (x = i),
 * 5 = 1-4-3-2 (z = k), 6 = 5-6-7-8 (z = k + 1). Positions: x = lx i / nx. */
#include <stdio.h>
#include <stdlib.h>
#include <exodusII.h>

static int check(int code, const char *what)
{
  if (code < 0) {
    fprintf(stderr, "exodus_box: %s failed (%d)\n", what, code);
    exit(1);
  }
  return code;
}

int main(int argc, char **argv)
{
  if (argc != 8) {
    fprintf(stderr, "usage: exodus_box NX NY NZ LX LY LZ OUT.exo\n");
    return 2;
  }
  int nx = atoi(argv[1]), ny = atoi(argv[2]), nz = atoi(argv[3]);
  double lx = atof(argv[4]), ly = atof(argv[5]), lz = atof(argv[6]);
  int comp_ws = 8, io_ws = 8;
  long nnode = (long)(nx + 1) * (ny + 1) * (nz + 1), nelem = (long)nx * ny * nz;
  int exoid = check(ex_create(argv[7], EX_CLOBBER, &comp_ws, &io_ws), "ex_create");
  check(ex_put_init(exoid, "impact3d test box", 3, nnode, nelem, 1, 0, 6), "ex_put_init");

  double *x = malloc(nnode * sizeof *x), *y = malloc(nnode * sizeof *y),
         *z = malloc(nnode * sizeof *z);
  for (int k = 0; k <= nz; k++)
    for (int j = 0; j <= ny; j++)
      for (int i = 0; i <= nx; i++) {
        long n = i + (nx + 1L) * (j + (ny + 1L) * k);
        x[n] = lx * i / nx;
        y[n] = ly * j / ny;
        z[n] = lz * k / nz;
      }
  check(ex_put_coord(exoid, x, y, z), "ex_put_coord");
  free(x); free(y); free(z);

  check(ex_put_block(exoid, EX_ELEM_BLOCK, 1, "HEX8", nelem, 8, 0, 0, 0), "ex_put_block");
  int *conn = malloc(8 * nelem * sizeof *conn);
#define NODE(i, j, k) (1 + (i) + (nx + 1) * ((j) + (ny + 1) * (k)))
  long e = 0;
  for (int k = 0; k < nz; k++)
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++, e++) {
        int *c = conn + 8 * e;
        c[0] = NODE(i, j, k); c[1] = NODE(i + 1, j, k);
        c[2] = NODE(i + 1, j + 1, k); c[3] = NODE(i, j + 1, k);
        c[4] = NODE(i, j, k + 1); c[5] = NODE(i + 1, j, k + 1);
        c[6] = NODE(i + 1, j + 1, k + 1); c[7] = NODE(i, j + 1, k + 1);
      }
  check(ex_put_conn(exoid, EX_ELEM_BLOCK, 1, conn, NULL, NULL), "ex_put_conn");
  free(conn);
  check(ex_put_name(exoid, EX_ELEM_BLOCK, 1, "all"), "ex_put_name");

  static const char *names[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  static const int sides[6] = {4, 2, 1, 3, 5, 6};
  int *elem = malloc(nelem * sizeof *elem), *side = malloc(nelem * sizeof *side);
  for (int s = 0; s < 6; s++) {
    long n = 0;
    e = 0;
    for (int k = 0; k < nz; k++)
      for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++, e++) {
          int on = (s == 0 && i == 0) || (s == 1 && i == nx - 1) || (s == 2 && j == 0) ||
                   (s == 3 && j == ny - 1) || (s == 4 && k == 0) || (s == 5 && k == nz - 1);
          if (!on) continue;
          elem[n] = (int)e + 1;
          side[n] = sides[s];
          n++;
        }
    check(ex_put_set_param(exoid, EX_SIDE_SET, s + 1, n, 0), "ex_put_set_param");
    check(ex_put_set(exoid, EX_SIDE_SET, s + 1, elem, side), "ex_put_set");
    check(ex_put_name(exoid, EX_SIDE_SET, s + 1, names[s]), "ex_put_name");
  }
  free(elem); free(side);
  check(ex_close(exoid), "ex_close");
  return 0;
}
