!> This rank's contiguous range of the global zone ids as generated or read,
!> before partitioning: the zones' global node ids, the positions of their
!> corners, their blocks and their faces in named face sets. Every rank
!> holds only its range (the global mesh is never assembled); parts are
!> numbered one after the other, nodes of a part after the previous parts'
!> nodes, as mesh_append numbers them.
module mesh_range
  use core_kinds, only: rk, ik, i8
  use core_status, only: status_t
  use mesh_global, only: global_mesh_t, box_spec_t, interval_points, box_position, NAME_LEN
  use parallel_env, only: par_rank, par_size
  use parallel_route, only: par_block_range
  implicit none
  private
  public :: range_init, range_add_box, range_add_global, range_set_index, box_sizes, &
      range_grow_faces, box_set_counts

  type, public :: mesh_range_t
    integer(i8) :: nzone_global = 0 !< zones of the whole mesh
    integer(i8) :: nnode_global = 0 !< nodes of the whole mesh
    integer(i8) :: first = 1 !< global id of this rank's first zone
    integer :: nzone = 0 !< zones in this rank's range
    integer(i8), allocatable :: conn(:, :) !< (8, nzone) global node ids
    integer(ik), allocatable :: zone_block(:) !< block of each zone (0 = none yet)
    real(rk), allocatable :: corner_x(:, :, :) !< (3, 8, nzone) corner positions
    integer :: nset = 0 !< named face sets (the same list on every rank)
    character(len=NAME_LEN), allocatable :: set_name(:)
    integer(i8), allocatable :: set_count(:) !< faces of each set over the whole mesh
    integer :: nface = 0 !< set faces of this range's zones
    integer, allocatable :: face_set(:) !< set of each
    integer, allocatable :: face_zone(:) !< zone (1..nzone in the range)
    integer, allocatable :: face_face(:) !< face 1..6 (mesh_geometry order)
    integer(i8), allocatable :: face_ord(:) !< 1-based position in its set's global list
  end type mesh_range_t

contains

  !> An empty range of this rank's share of nzone_global zones.
  subroutine range_init(range, nzone_global, nnode_global)
    type(mesh_range_t), intent(out) :: range
    integer(i8), intent(in) :: nzone_global, nnode_global
    range%nzone_global = nzone_global
    range%nnode_global = nnode_global
    call par_block_range(nzone_global, par_size(), par_rank(), range%first, range%nzone)
    allocate(range%conn(8, range%nzone), range%zone_block(range%nzone))
    allocate(range%corner_x(3, 8, range%nzone))
    range%conn = 0
    range%zone_block = 0
    range%corner_x = 0.0_rk
    allocate(range%set_name(0), range%set_count(0))
    allocate(range%face_set(0), range%face_zone(0), range%face_face(0), range%face_ord(0))
  end subroutine range_init

  !> The index of set name in the range's list, appended (with no faces yet)
  !> when new.
  integer function range_set_index(range, name) result(k)
    type(mesh_range_t), intent(inout) :: range
    character(len=*), intent(in) :: name
    do k = 1, range%nset
      if (range%set_name(k) == name) return
    end do
    range%nset = range%nset + 1
    k = range%nset
    range%set_name = [character(len=NAME_LEN) :: range%set_name, name]
    range%set_count = [range%set_count, 0_i8]
  end function range_set_index

  !> Zones, nodes and the face counts of its six sets (xmin, xmax, ymin,
  !> ymax, zmin, zmax) of a box, without building it.
  subroutine box_sizes(spec, nx, ny, nz)
    type(box_spec_t), intent(in) :: spec
    integer, intent(out) :: nx, ny, nz
    nx = sum(spec%zones(1:spec%nint(1), 1))
    ny = sum(spec%zones(1:spec%nint(2), 2))
    nz = sum(spec%zones(1:spec%nint(3), 3))
  end subroutine box_sizes

  !> Faces in the box's sets xmin, xmax, ymin, ymax, zmin, zmax.
  pure function box_set_counts(nx, ny, nz) result(c)
    integer, intent(in) :: nx, ny, nz
    integer(i8) :: c(6)
    c = int([ny * nz, ny * nz, nx * nz, nx * nz, nx * ny, nx * ny], i8)
  end function box_set_counts

  !> The zones of a box part (global ids zone0+1 .. zone0+nx ny nz, nodes
  !> node0+1 ..) that lie in this rank's range, numbered as mesh_make_box
  !> numbers them; its six sets go to the range's sets sets(:, f) (up to two:
  !> the plain and the prefixed name, 0 = none), after ord0(:, f) faces of
  !> earlier parts. lo..hi are the range positions filled (hi < lo: none).
  subroutine range_add_box(range, spec, zone0, node0, sets, ord0, lo, hi)
    type(mesh_range_t), intent(inout) :: range
    type(box_spec_t), intent(in) :: spec
    integer(i8), intent(in) :: zone0, node0
    integer, intent(in) :: sets(2, 6)
    integer(i8), intent(in) :: ord0(2, 6)
    integer, intent(out) :: lo, hi
    real(rk), allocatable :: px(:), py(:), pz(:)
    integer :: nx, ny, nz, i, j, k, c, f, m, nnew, pos
    integer(i8) :: g, zfirst, zlast, local
    integer, parameter :: CORNER(3, 8) = reshape([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, &
        0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1], [3, 8])
    integer, parameter :: FACE_OF_SET(6) = [6, 4, 3, 5, 1, 2]
    logical :: on(6)
    integer(i8) :: ord(6)

    call interval_points(spec%nint(1), spec%breaks(:, 1), spec%zones(:, 1), spec%ratio(:, 1), px)
    call interval_points(spec%nint(2), spec%breaks(:, 2), spec%zones(:, 2), spec%ratio(:, 2), py)
    call interval_points(spec%nint(3), spec%breaks(:, 3), spec%zones(:, 3), spec%ratio(:, 3), pz)
    nx = size(px) - 1
    ny = size(py) - 1
    nz = size(pz) - 1
    zfirst = max(zone0 + 1, range%first)
    zlast = min(zone0 + int(nx, i8) * ny * nz, range%first + range%nzone - 1)
    lo = int(zfirst - range%first) + 1
    hi = int(zlast - range%first) + 1
    if (zlast < zfirst) return
    ! Count the set faces first.
    nnew = 0
    do g = zfirst, zlast
      call ijk(g - zone0, i, j, k)
      on = [i == 0, i == nx - 1, j == 0, j == ny - 1, k == 0, k == nz - 1]
      do f = 1, 6
        if (on(f)) nnew = nnew + count(sets(:, f) > 0)
      end do
    end do
    call range_grow_faces(range, nnew)
    pos = range%nface
    do g = zfirst, zlast
      local = g - range%first + 1
      call ijk(g - zone0, i, j, k)
      do c = 1, 8
        range%conn(c, local) = node0 + node_id(i + CORNER(1, c), j + CORNER(2, c), &
            k + CORNER(3, c))
        range%corner_x(:, c, local) = box_position(spec, px, py, pz, i + CORNER(1, c), &
            j + CORNER(2, c), k + CORNER(3, c))
      end do
      on = [i == 0, i == nx - 1, j == 0, j == ny - 1, k == 0, k == nz - 1]
      ord = int([1 + j + ny * k, 1 + j + ny * k, 1 + i + nx * k, 1 + i + nx * k, &
          1 + i + nx * j, 1 + i + nx * j], i8)
      do f = 1, 6
        if (.not. on(f)) cycle
        do m = 1, 2
          if (sets(m, f) == 0) cycle
          pos = pos + 1
          range%face_set(pos) = sets(m, f)
          range%face_zone(pos) = int(local)
          range%face_face(pos) = FACE_OF_SET(f)
          range%face_ord(pos) = ord0(m, f) + ord(f)
        end do
      end do
    end do
    range%nface = pos

  contains

    !> 0-based (i, j, k) of the part's zone id z (1-based, i fastest).
    pure subroutine ijk(z, ii, jj, kk)
      integer(i8), intent(in) :: z
      integer, intent(out) :: ii, jj, kk
      integer(i8) :: r
      r = z - 1
      ii = int(modulo(r, int(nx, i8)))
      r = r / nx
      jj = int(modulo(r, int(ny, i8)))
      kk = int(r / ny)
    end subroutine ijk

    pure integer(i8) function node_id(ii, jj, kk)
      integer, intent(in) :: ii, jj, kk
      node_id = 1_i8 + ii + int(nx + 1, i8) * (jj + int(ny + 1, i8) * kk)
    end function node_id


  end subroutine range_add_box

  !> The zones of a part built whole (curved generators, imported files)
  !> that lie in this rank's range; the part's set k goes to the range's
  !> sets sets(:, k) after ord0(:, k) faces of earlier parts.
  subroutine range_add_global(range, piece, zone0, node0, sets, ord0, lo, hi)
    type(mesh_range_t), intent(inout) :: range
    type(global_mesh_t), intent(in) :: piece
    integer(i8), intent(in) :: zone0, node0
    integer, intent(in) :: sets(:, :) !< (2, piece%nset)
    integer(i8), intent(in) :: ord0(:, :) !< (2, piece%nset)
    integer, intent(out) :: lo, hi
    integer(i8) :: zfirst, zlast, g, local
    integer :: s, k, m, z, pos, nnew
    zfirst = max(zone0 + 1, range%first)
    zlast = min(zone0 + piece%nzone, range%first + range%nzone - 1)
    lo = int(zfirst - range%first) + 1
    hi = int(zlast - range%first) + 1
    if (zlast < zfirst) return
    do g = zfirst, zlast
      local = g - range%first + 1
      z = int(g - zone0)
      range%conn(:, local) = node0 + int(piece%connectivity(:, z), i8)
      range%corner_x(:, :, local) = piece%coordinates(:, piece%connectivity(:, z))
      range%zone_block(local) = piece%zone_block(z)
    end do
    nnew = 0
    do k = 1, piece%nset
      do s = piece%set_start(k), piece%set_start(k + 1) - 1
        if (piece%set_zone(s) + zone0 >= zfirst .and. piece%set_zone(s) + zone0 <= zlast) &
            nnew = nnew + count(sets(:, k) > 0)
      end do
    end do
    call range_grow_faces(range, nnew)
    pos = range%nface
    do k = 1, piece%nset
      do s = piece%set_start(k), piece%set_start(k + 1) - 1
        g = piece%set_zone(s) + zone0
        if (g < zfirst .or. g > zlast) cycle
        do m = 1, 2
          if (sets(m, k) == 0) cycle
          pos = pos + 1
          range%face_set(pos) = sets(m, k)
          range%face_zone(pos) = int(g - range%first) + 1
          range%face_face(pos) = int(piece%set_face(s))
          range%face_ord(pos) = ord0(m, k) + (s - piece%set_start(k) + 1)
        end do
      end do
    end do
    range%nface = pos
  end subroutine range_add_global

  !> Room for n more set faces.
  subroutine range_grow_faces(range, n)
    type(mesh_range_t), intent(inout) :: range
    integer, intent(in) :: n
    integer :: m
    integer, allocatable :: a(:)
    integer(i8), allocatable :: b(:)
    m = range%nface
    if (size(range%face_set) >= m + n) return
    allocate(a(m + n))
    a(:m) = range%face_set(:m)
    call move_alloc(a, range%face_set)
    allocate(a(m + n))
    a(:m) = range%face_zone(:m)
    call move_alloc(a, range%face_zone)
    allocate(a(m + n))
    a(:m) = range%face_face(:m)
    call move_alloc(a, range%face_face)
    allocate(b(m + n))
    b(:m) = range%face_ord(:m)
    call move_alloc(b, range%face_ord)
  end subroutine range_grow_faces

end module mesh_range
