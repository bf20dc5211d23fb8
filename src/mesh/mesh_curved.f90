!> Hex meshes of curved bodies without degenerate zones: a solid rod (O-grid),
!> a thick tube, a spherical shell octant (cubed-sphere patches), a ball octant
!> (cube core and three patches out to the sphere) and the octant of a box
!> minus a ball (three patches from the sphere out to the box faces).
!>
!> Each body is assembled from structured blocks (logical i, j, k). A block
!> whose first hex comes out left-handed is mirrored in i, so every hex has the
!> positive (VTK) node order. Nodes that blocks share are merged by position
!> (within 1e-10 of the body size; shared nodes are computed by the same
!> formulas, so they agree to round-off). Nodes are numbered in order of first
!> appearance and zones block by block, i fastest. Nodes on a circle or sphere
!> are computed as radius times a unit direction, and nodes on a symmetry
!> plane have that coordinate exactly zero. zone_block is left 0: the caller
!> assigns blocks.
module mesh_curved
  use core_kinds, only: rk, ik
  use core_status, only: status_t
  use core_sort, only: sort_order
  use core_text, only: real_text => to_text, int_text => to_text
  use mesh_geometry, only: hex_volume
  use mesh_global, only: global_mesh_t, interval_points, NAME_LEN
  implicit none
  private
  public :: rod_spec_t, tube_spec_t, shell_spec_t, ball_spec_t, box_minus_ball_spec_t
  public :: mesh_make_rod, mesh_make_tube, mesh_make_shell_octant, mesh_make_ball_octant
  public :: mesh_make_box_minus_ball

  real(rk), parameter :: PI = acos(-1.0_rk)
  !> Angle between a bulged core edge and the straight one at the core corner:
  !> 15 degrees makes all three zones meeting at that corner 120 degrees wide.
  real(rk), parameter :: CORE_BULGE = PI / 12.0_rk
  !> Nodes closer than this fraction of the body size are one node.
  real(rk), parameter :: MERGE_TOLERANCE = 1.0e-10_rk
  !> Largest accepted |(|axis| - 1)|.
  real(rk), parameter :: UNIT_TOLERANCE = 1.0e-6_rk

  !> Solid circular cylinder along z: a square core (edges bulging toward the
  !> circle) inside a ring of zones mapped to the circle (an O-grid).
  type :: rod_spec_t
    real(rk) :: radius = 1.0_rk !< R
    real(rk) :: length = 4.0_rk !< L: the rod spans z0 <= z <= z0 + L
    real(rk) :: z0 = 0.0_rk !< z of the bottom face
    character(len=16) :: sector = 'quarter' !< 'quarter' (x >= 0, y >= 0) or 'full'
    integer :: n_core = 6 !< zones along each core edge (a full rod has 2 n_core across)
    integer :: n_radial = 4 !< zones across the ring, core to circle
    integer :: n_axial = 40 !< zones along z
    real(rk) :: axial_ratio = 1.0_rk !< last/first zone length along z
    real(rk) :: core_fraction = 0.55_rk !< the core corner is at (f R, f R), 0.3 <= f <= 0.65
  end type rod_spec_t

  !> Thick tube ri <= r <= ro along an axis, full or cut by planes through the axis.
  !> In the local frame (e1, e2, axis) theta = 0 is e1; the default frame is x, y, z.
  type :: tube_spec_t
    real(rk) :: ri = 0.8_rk !< inner radius
    real(rk) :: ro = 1.0_rk !< outer radius
    real(rk) :: length = 8.0_rk !< length along the axis
    character(len=16) :: sector = 'full' !< 'full', 'half' (local y >= 0) or 'quarter' (x, y >= 0)
    integer :: n_theta = 64 !< zones around (over the sector)
    integer :: n_radial = 3 !< zones across the wall
    integer :: n_axial = 80 !< zones along the axis
    real(rk) :: axial_ratio = 1.0_rk !< last/first zone length along the axis
    real(rk) :: axis(3) = [0.0_rk, 0.0_rk, 1.0_rk] !< unit axis direction (local z)
    real(rk) :: origin(3) = 0.0_rk !< centre of the bottom face
    !> Direction of theta = 0 (local x), projected normal to the axis; all zero
    !> picks the global axis least aligned with the tube axis (x for a z tube).
    real(rk) :: radial_reference(3) = 0.0_rk
  end type tube_spec_t

  !> Spherical shell octant (x, y, z >= 0) between ri and ro, centred at 0.
  type :: shell_spec_t
    real(rk) :: ri = 8.0_rk !< inner radius
    real(rk) :: ro = 10.0_rk !< outer radius
    integer :: n_patch = 10 !< zones along each edge of the three surface patches
    integer :: n_radial = 8 !< zones from ri to ro
    real(rk) :: radial_ratio = 1.0_rk !< last/first zone thickness (outward)
  end type shell_spec_t

  !> Ball octant (x, y, z >= 0) of radius R centred at 0: a cube core
  !> [0, a]^3 and three patches, each joining one outer core face to the
  !> sphere by straight lines (the 3D analogue of the rod's O-grid).
  type :: ball_spec_t
    real(rk) :: radius = 0.5_rk !< R
    integer :: n_core = 8 !< zones along each core edge (and each patch edge on the sphere)
    integer :: n_radial = 6 !< zones from the core face to the sphere
    real(rk) :: radial_ratio = 1.0_rk !< last/first zone thickness (outward)
    real(rk) :: core_fraction = 0.45_rk !< a = f R, 0.2 <= f <= 0.5
  end type ball_spec_t

  !> Octant of the box [0, L]^3 minus the ball r < R (R < L): three patches,
  !> each mapping a cubed-sphere patch of the sphere to one outer box face
  !> along rays from the origin.
  type :: box_minus_ball_spec_t
    real(rk) :: radius = 0.5_rk !< R, the sphere
    real(rk) :: length = 1.2_rk !< L, the box edge
    integer :: n_patch = 12 !< zones along each edge of the three patches
    integer :: n_radial = 16 !< zones from the sphere to the box faces
    real(rk) :: radial_ratio = 1.0_rk !< last/first zone length along a ray (outward)
  end type box_minus_ball_spec_t

  !> One structured block of n(1) x n(2) x n(3) hexes.
  type :: block_t
    integer :: n(3) = 0 !< zones in i, j, k
    real(rk), allocatable :: x(:, :, :, :) !< (3, 0:n1, 0:n2, 0:n3) node coordinates
    !> Set index of each block face (mesh_geometry face order: k-, k+, j-, i+,
    !> j+, i-), 0 for faces glued to another block.
    integer :: face_set(6) = 0
  end type block_t

contains

  !> Solid rod along z. Quarter: one core block and two ring blocks (the ring
  !> split on the 45 degree diagonal); full: the quarter rotated four times.
  !> Sets: side, bottom, top (+ xsym, ysym for the quarter).
  subroutine mesh_make_rod(spec, mesh, status)
    type(rod_spec_t), intent(in) :: spec
    type(global_mesh_t), intent(inout) :: mesh
    type(status_t), intent(inout) :: status
    integer, parameter :: SIDE = 1, BOTTOM = 2, TOP = 3, XSYM = 4, YSYM = 5
    type(block_t), allocatable :: blocks(:)
    real(rk), allocatable :: z(:)
    real(rk) :: a, rho, xc, b, p(2), u, v
    integer :: nerr, nq, q, nc, nr, nz, i, j, k, xset, yset
    logical :: full

    call mesh%free()
    nerr = status%count
    call require(status, spec%radius > 0.0_rk, 'rod: radius must be > 0 (got ' // &
        real_text(spec%radius) // ')')
    call require(status, spec%length > 0.0_rk, 'rod: length must be > 0 (got ' // &
        real_text(spec%length) // ')')
    call require(status, spec%sector == 'quarter' .or. spec%sector == 'full', &
        "rod: sector must be 'quarter' or 'full' (got '" // trim(spec%sector) // "')")
    call require_count(status, 'rod: n_core', spec%n_core, 1)
    call require_count(status, 'rod: n_radial', spec%n_radial, 1)
    call require_count(status, 'rod: n_axial', spec%n_axial, 1)
    call require(status, spec%axial_ratio > 0.0_rk, 'rod: axial_ratio must be > 0 (got ' // &
        real_text(spec%axial_ratio) // ')')
    call require(status, spec%core_fraction >= 0.3_rk .and. spec%core_fraction <= 0.65_rk, &
        'rod: core_fraction must be in [0.3, 0.65] (got ' // real_text(spec%core_fraction) // ')')
    if (status%count > nerr) return

    full = spec%sector == 'full'
    nc = spec%n_core
    nr = spec%n_radial
    nz = spec%n_axial
    call interval_points(1, [spec%z0, spec%z0 + spec%length], [nz], [spec%axial_ratio], z)
    ! Core edge x = a bulged into an arc of radius rho centred at (xc, 0): from
    ! (b, 0) on the x axis to the core corner (a, a).
    a = spec%core_fraction * spec%radius
    rho = a / sin(CORE_BULGE)
    xc = a - rho * cos(CORE_BULGE)
    b = xc + rho
    xset = XSYM
    yset = YSYM
    nq = 1
    if (full) then
      xset = 0
      yset = 0
      nq = 4
    end if
    allocate(blocks(3 * nq))
    do q = 0, nq - 1
      ! Core: i along x, j along y.
      call block_new(blocks(3 * q + 1), nc, nc, nz, [BOTTOM, TOP, yset, 0, 0, xset])
      ! Ring below the diagonal: i radial (core to circle), j counter-clockwise.
      call block_new(blocks(3 * q + 2), nr, nc, nz, [BOTTOM, TOP, yset, SIDE, 0, 0])
      ! Ring above the diagonal: the mirror image of the one below in x = y.
      call block_new(blocks(3 * q + 3), nr, nc, nz, [BOTTOM, TOP, xset, SIDE, 0, 0])
      do j = 0, nc
        v = real(j, rk) / real(nc, rk)
        do i = 0, nc
          u = real(i, rk) / real(nc, rk)
          p = rotate_quarters(core_point(u, v), q)
          do k = 0, nz
            blocks(3 * q + 1)%x(:, i, j, k) = [p, z(k)]
          end do
        end do
        do i = 0, nr
          u = real(i, rk) / real(nr, rk)
          p = ring_point(u, v)
          do k = 0, nz
            blocks(3 * q + 2)%x(:, i, j, k) = [rotate_quarters(p, q), z(k)]
            blocks(3 * q + 3)%x(:, i, j, k) = [rotate_quarters([p(2), p(1)], q), z(k)]
          end do
        end do
      end do
    end do
    if (full) then
      call assemble(blocks, [character(len=NAME_LEN) :: 'side', 'bottom', 'top'], &
          max(spec%radius, spec%length), mesh)
    else
      call assemble(blocks, [character(len=NAME_LEN) :: 'side', 'bottom', 'top', 'xsym', &
          'ysym'], max(spec%radius, spec%length), mesh)
    end if

  contains

    !> Point s (0..1) of the bulged core edge, from (b, 0) to (a, a).
    pure function core_edge(s) result(pt)
      real(rk), intent(in) :: s
      real(rk) :: pt(2)
      pt = [xc + rho * cos(s * CORE_BULGE), rho * sin(s * CORE_BULGE)]
    end function core_edge

    !> Core point (u, v) in [0,1]^2: transfinite (Coons) interpolation of the
    !> straight edges on the axes and the two bulged edges.
    pure function core_point(uu, vv) result(pt)
      real(rk), intent(in) :: uu, vv
      real(rk) :: pt(2), right(2), upper(2)
      right = core_edge(vv)
      upper = core_edge(uu)
      upper = [upper(2), upper(1)]
      pt = (1.0_rk - vv) * [uu * b, 0.0_rk] + vv * upper + (1.0_rk - uu) * [0.0_rk, vv * b] &
          + uu * right - (uu * (1.0_rk - vv) * [b, 0.0_rk] + (1.0_rk - uu) * vv * [0.0_rk, b] &
          + uu * vv * [a, a])
    end function core_point

    !> Ring point: fraction t of the straight way from the core edge point s to
    !> the circle at angle s pi/4 (t = 1 gives the circle point exactly).
    pure function ring_point(t, s) result(pt)
      real(rk), intent(in) :: t, s
      real(rk) :: pt(2)
      pt = (1.0_rk - t) * core_edge(s) + t * (spec%radius * [cos(s * 0.25_rk * PI), &
          sin(s * 0.25_rk * PI)])
    end function ring_point

  end subroutine mesh_make_rod

  !> Thick tube: one block, i radial, j around, k along the axis; a full tube
  !> closes on itself at theta = 0. Sets: inner, outer, bottom, top, and the
  !> cut planes (half: ysym for both cuts; quarter: ysym at theta = 0 and xsym
  !> at theta = 90 degrees; local axes, i.e. the global x, y planes by default).
  subroutine mesh_make_tube(spec, mesh, status)
    type(tube_spec_t), intent(in) :: spec
    type(global_mesh_t), intent(inout) :: mesh
    type(status_t), intent(inout) :: status
    integer, parameter :: INNER = 1, OUTER = 2, BOTTOM = 3, TOP = 4
    type(block_t) :: blocks(1)
    real(rk), allocatable :: r(:), z(:)
    real(rk) :: axis(3), e1(3), e2(3), c(2), length_axis, projected
    integer :: nerr, quarters, min_theta, i, j, k, start_set, end_set
    character(len=NAME_LEN), allocatable :: names(:)

    call mesh%free()
    nerr = status%count
    call require(status, spec%ri > 0.0_rk, 'tube: ri must be > 0 (got ' // &
        real_text(spec%ri) // ')')
    call require(status, spec%ro > spec%ri, 'tube: ro must be > ri (got ri = ' // &
        real_text(spec%ri) // ', ro = ' // real_text(spec%ro) // ')')
    call require(status, spec%length > 0.0_rk, 'tube: length must be > 0 (got ' // &
        real_text(spec%length) // ')')
    select case (spec%sector)
    case ('full')
      quarters = 4
      min_theta = 3
    case ('half')
      quarters = 2
      min_theta = 2
    case ('quarter')
      quarters = 1
      min_theta = 1
    case default
      quarters = 0
      min_theta = 1
      call status%add("tube: sector must be 'full', 'half' or 'quarter' (got '" // &
          trim(spec%sector) // "')")
    end select
    call require_count(status, 'tube: n_theta', spec%n_theta, min_theta)
    call require_count(status, 'tube: n_radial', spec%n_radial, 1)
    call require_count(status, 'tube: n_axial', spec%n_axial, 1)
    call require(status, spec%axial_ratio > 0.0_rk, 'tube: axial_ratio must be > 0 (got ' // &
        real_text(spec%axial_ratio) // ')')
    length_axis = norm2(spec%axis)
    call require(status, abs(length_axis - 1.0_rk) <= UNIT_TOLERANCE, &
        'tube: axis must be a unit vector (|axis| = ' // real_text(length_axis) // ')')
    if (any(spec%radial_reference /= 0.0_rk) .and. length_axis > 0.0_rk) then
      projected = norm2(spec%radial_reference - dot_product(spec%radial_reference, &
          spec%axis) * spec%axis / length_axis**2)
      call require(status, projected > UNIT_TOLERANCE * norm2(spec%radial_reference), &
          'tube: radial_reference must not be parallel to axis (or all zero for automatic)')
    end if
    if (status%count > nerr) return

    ! Right-handed frame (e1, e2, axis).
    axis = spec%axis / length_axis
    if (all(spec%radial_reference == 0.0_rk)) then
      e1 = 0.0_rk
      e1(minloc(abs(axis), dim=1)) = 1.0_rk
    else
      e1 = spec%radial_reference
    end if
    e1 = e1 - dot_product(e1, axis) * axis
    e1 = e1 / norm2(e1)
    e2 = cross(axis, e1)

    start_set = 0
    end_set = 0
    select case (quarters)
    case (4)
      allocate(names(4))
    case (2)
      allocate(names(5))
      names(5) = 'ysym'
      start_set = 5
      end_set = 5
    case default
      allocate(names(6))
      names(5:6) = [character(len=NAME_LEN) :: 'xsym', 'ysym']
      start_set = 6
      end_set = 5
    end select
    names(1:4) = [character(len=NAME_LEN) :: 'inner', 'outer', 'bottom', 'top']
    call interval_points(1, [spec%ri, spec%ro], [spec%n_radial], [1.0_rk], r)
    call interval_points(1, [0.0_rk, spec%length], [spec%n_axial], [spec%axial_ratio], z)
    call block_new(blocks(1), spec%n_radial, spec%n_theta, spec%n_axial, &
        [BOTTOM, TOP, start_set, OUTER, end_set, INNER])
    do j = 0, spec%n_theta
      c = circle_point(j, spec%n_theta, quarters)
      do k = 0, spec%n_axial
        do i = 0, spec%n_radial
          blocks(1)%x(:, i, j, k) = spec%origin + (r(i) * c(1)) * e1 + (r(i) * c(2)) * e2 &
              + z(k) * axis
        end do
      end do
    end do
    call assemble(blocks, names, max(spec%ro, spec%length, maxval(abs(spec%origin))), mesh)
  end subroutine mesh_make_tube

  !> Spherical shell octant: three cubed-sphere patches (equiangular gnomonic,
  !> one around each axis) meeting at the (1,1,1) direction; i, j the two
  !> patch angles, k radial. Sets: inner, outer, xsym, ysym, zsym.
  subroutine mesh_make_shell_octant(spec, mesh, status)
    type(shell_spec_t), intent(in) :: spec
    type(global_mesh_t), intent(inout) :: mesh
    type(status_t), intent(inout) :: status
    integer, parameter :: INNER = 1, OUTER = 2, XSYM = 3, YSYM = 4, ZSYM = 5
    type(block_t) :: blocks(3)
    real(rk), allocatable :: r(:), t(:)
    real(rk) :: d(3, 3)
    integer :: nerr, np, nr, i, j, k, patch

    call mesh%free()
    nerr = status%count
    call require(status, spec%ri > 0.0_rk, 'shell: ri must be > 0 (got ' // &
        real_text(spec%ri) // ')')
    call require(status, spec%ro > spec%ri, 'shell: ro must be > ri (got ri = ' // &
        real_text(spec%ri) // ', ro = ' // real_text(spec%ro) // ')')
    call require_count(status, 'shell: n_patch', spec%n_patch, 1)
    call require_count(status, 'shell: n_radial', spec%n_radial, 1)
    call require(status, spec%radial_ratio > 0.0_rk, 'shell: radial_ratio must be > 0 (got ' &
        // real_text(spec%radial_ratio) // ')')
    if (status%count > nerr) return

    np = spec%n_patch
    nr = spec%n_radial
    call interval_points(1, [spec%ri, spec%ro], [nr], [spec%radial_ratio], r)
    ! Tangents of the equiangular patch coordinates, exact at 0 and 1.
    call patch_tangents(np, t)
    ! Patch 1 around x: (1, tan i, tan j); 2 around y: (tan i, 1, tan j);
    ! 3 around z: (tan i, tan j, 1).
    call block_new(blocks(1), np, np, nr, [INNER, OUTER, ZSYM, 0, 0, YSYM])
    call block_new(blocks(2), np, np, nr, [INNER, OUTER, ZSYM, 0, 0, XSYM])
    call block_new(blocks(3), np, np, nr, [INNER, OUTER, YSYM, 0, 0, XSYM])
    do j = 0, np
      do i = 0, np
        d = patch_directions(t(i), t(j))
        do patch = 1, 3
          d(:, patch) = d(:, patch) / sqrt(sum(d(:, patch)**2))
          do k = 0, nr
            blocks(patch)%x(:, i, j, k) = r(k) * d(:, patch)
          end do
        end do
      end do
    end do
    call assemble(blocks, [character(len=NAME_LEN) :: 'inner', 'outer', 'xsym', 'ysym', &
        'zsym'], spec%ro, mesh)
  end subroutine mesh_make_shell_octant


  !> Ball octant: the core block (i, j, k along x, y, z) and three patches
  !> (i, j across the core face, k from the core face to the sphere; patch 1
  !> on the face x = a, 2 on y = a, 3 on z = a). The sphere nodes are
  !> equiangular cubed-sphere points, radius times a unit direction.
  !> Sets: outer (the sphere), xmin, ymin, zmin.
  subroutine mesh_make_ball_octant(spec, mesh, status)
    type(ball_spec_t), intent(in) :: spec
    type(global_mesh_t), intent(inout) :: mesh
    type(status_t), intent(inout) :: status
    integer, parameter :: OUTER = 1, XMIN = 2, YMIN = 3, ZMIN = 4
    type(block_t) :: blocks(4)
    real(rk), allocatable :: s(:), t(:)
    real(rk) :: a, d(3, 3), core(3, 3), across
    integer :: nerr, nc, nr, i, j, k, patch

    call mesh%free()
    nerr = status%count
    call require(status, spec%radius > 0.0_rk, 'ball: radius must be > 0 (got ' // &
        real_text(spec%radius) // ')')
    call require_count(status, 'ball: n_core', spec%n_core, 1)
    call require_count(status, 'ball: n_radial', spec%n_radial, 1)
    call require(status, spec%radial_ratio > 0.0_rk, 'ball: radial_ratio must be > 0 (got ' &
        // real_text(spec%radial_ratio) // ')')
    call require(status, spec%core_fraction >= 0.2_rk .and. spec%core_fraction <= 0.5_rk, &
        'ball: core_fraction must be in [0.2, 0.5] (got ' // real_text(spec%core_fraction) // &
        ')')
    if (status%count > nerr) return

    nc = spec%n_core
    nr = spec%n_radial
    a = spec%core_fraction * spec%radius
    call interval_points(1, [0.0_rk, 1.0_rk], [nr], [spec%radial_ratio], s)
    s(0) = 0.0_rk
    s(nr) = 1.0_rk
    call patch_tangents(nc, t)
    call block_new(blocks(1), nc, nc, nc, [ZMIN, 0, YMIN, 0, 0, XMIN])
    call block_new(blocks(2), nc, nc, nr, [0, OUTER, ZMIN, 0, 0, YMIN])
    call block_new(blocks(3), nc, nc, nr, [0, OUTER, ZMIN, 0, 0, XMIN])
    call block_new(blocks(4), nc, nc, nr, [0, OUTER, YMIN, 0, 0, XMIN])
    do k = 0, nc
      do j = 0, nc
        do i = 0, nc
          blocks(1)%x(:, i, j, k) = a * [core_coordinate(i), core_coordinate(j), &
              core_coordinate(k)]
        end do
      end do
    end do
    do j = 0, nc
      do i = 0, nc
        d = patch_directions(t(i), t(j))
        across = a * core_coordinate(i)
        core(:, 1) = [a, across, a * core_coordinate(j)]
        core(:, 2) = [across, a, a * core_coordinate(j)]
        core(:, 3) = [across, a * core_coordinate(j), a]
        do patch = 1, 3
          d(:, patch) = spec%radius * d(:, patch) / sqrt(sum(d(:, patch)**2))
          do k = 0, nr
            blocks(patch + 1)%x(:, i, j, k) = (1.0_rk - s(k)) * core(:, patch) &
                + s(k) * d(:, patch)
          end do
          ! The sphere node exactly radius times the unit direction.
          blocks(patch + 1)%x(:, i, j, nr) = d(:, patch)
        end do
      end do
    end do
    call assemble(blocks, [character(len=NAME_LEN) :: 'outer', 'xmin', 'ymin', 'zmin'], &
        spec%radius, mesh)

  contains

    !> Core node coordinate i / nc, exactly 0 and 1 at the ends.
    pure real(rk) function core_coordinate(ii)
      integer, intent(in) :: ii
      core_coordinate = real(ii, rk) / real(nc, rk)
    end function core_coordinate

  end subroutine mesh_make_ball_octant

  !> Box minus ball octant: three patches (i, j the equiangular patch angles,
  !> k along the ray from the sphere to the box face; patch 1 ends on x = L,
  !> 2 on y = L, 3 on z = L). Node (i, j, k) lies on the ray through the
  !> cubed-sphere direction (i, j); the sphere nodes are radius times the unit
  !> direction, the box nodes L (1, tan, tan) (the face coordinate exactly L).
  !> Sets: inner (the sphere), xmin, ymin, zmin, xmax, ymax, zmax.
  subroutine mesh_make_box_minus_ball(spec, mesh, status)
    type(box_minus_ball_spec_t), intent(in) :: spec
    type(global_mesh_t), intent(inout) :: mesh
    type(status_t), intent(inout) :: status
    integer, parameter :: INNER = 1, XMIN = 2, YMIN = 3, ZMIN = 4, XMAX = 5, YMAX = 6, ZMAX = 7
    type(block_t) :: blocks(3)
    real(rk), allocatable :: s(:), t(:)
    real(rk) :: d(3, 3), sphere(3)
    integer :: nerr, np, nr, i, j, k, patch

    call mesh%free()
    nerr = status%count
    call require(status, spec%radius > 0.0_rk, 'box_minus_ball: radius must be > 0 (got ' // &
        real_text(spec%radius) // ')')
    call require(status, spec%length > spec%radius, 'box_minus_ball: length must be > ' // &
        'radius (got radius = ' // real_text(spec%radius) // ', length = ' // &
        real_text(spec%length) // ')')
    call require_count(status, 'box_minus_ball: n_patch', spec%n_patch, 1)
    call require_count(status, 'box_minus_ball: n_radial', spec%n_radial, 1)
    call require(status, spec%radial_ratio > 0.0_rk, 'box_minus_ball: radial_ratio must be ' &
        // '> 0 (got ' // real_text(spec%radial_ratio) // ')')
    if (status%count > nerr) return

    np = spec%n_patch
    nr = spec%n_radial
    call interval_points(1, [0.0_rk, 1.0_rk], [nr], [spec%radial_ratio], s)
    s(0) = 0.0_rk
    s(nr) = 1.0_rk
    call patch_tangents(np, t)
    call block_new(blocks(1), np, np, nr, [INNER, XMAX, ZMIN, 0, 0, YMIN])
    call block_new(blocks(2), np, np, nr, [INNER, YMAX, ZMIN, 0, 0, XMIN])
    call block_new(blocks(3), np, np, nr, [INNER, ZMAX, YMIN, 0, 0, XMIN])
    do j = 0, np
      do i = 0, np
        d = patch_directions(t(i), t(j))
        do patch = 1, 3
          sphere = spec%radius * d(:, patch) / sqrt(sum(d(:, patch)**2))
          blocks(patch)%x(:, i, j, 0) = sphere
          do k = 1, nr
            blocks(patch)%x(:, i, j, k) = (1.0_rk - s(k)) * sphere + s(k) * spec%length &
                * d(:, patch)
          end do
          blocks(patch)%x(:, i, j, nr) = spec%length * d(:, patch)
        end do
      end do
    end do
    call assemble(blocks, [character(len=NAME_LEN) :: 'inner', 'xmin', 'ymin', 'zmin', &
        'xmax', 'ymax', 'zmax'], spec%length, mesh)
  end subroutine mesh_make_box_minus_ball

  ! ---------------------------------------------------------------- helpers

  !> Tangents of the equiangular cubed-sphere patch coordinates i pi / (4 n),
  !> i = 0..n, exactly 0 and 1 at the ends.
  pure subroutine patch_tangents(n, t)
    integer, intent(in) :: n
    real(rk), allocatable, intent(out) :: t(:) !< (0:n)
    integer :: i
    allocate(t(0:n))
    do i = 0, n
      t(i) = tan(0.25_rk * PI * real(i, rk) / real(n, rk))
    end do
    t(0) = 0.0_rk
    t(n) = 1.0_rk
  end subroutine patch_tangents

  !> Unnormalised directions of the point (ti, tj) of the three equiangular
  !> octant patches: around x (1, ti, tj), around y (ti, 1, tj), around z (ti, tj, 1).
  pure function patch_directions(ti, tj) result(d)
    real(rk), intent(in) :: ti, tj
    real(rk) :: d(3, 3)
    d(:, 1) = [1.0_rk, ti, tj]
    d(:, 2) = [ti, 1.0_rk, tj]
    d(:, 3) = [ti, tj, 1.0_rk]
  end function patch_directions

  !> Allocate a block of n1 x n2 x n3 zones with the given face sets.
  subroutine block_new(block, n1, n2, n3, face_set)
    type(block_t), intent(inout) :: block
    integer, intent(in) :: n1, n2, n3
    integer, intent(in) :: face_set(6)
    if (allocated(block%x)) deallocate(block%x)
    block%n = [n1, n2, n3]
    allocate(block%x(3, 0:n1, 0:n2, 0:n3))
    block%x = 0.0_rk
    block%face_set = face_set
  end subroutine block_new

  !> Corners of hex (i, j, k) of a block in VTK order.
  pure function block_hex(block, i, j, k) result(x)
    type(block_t), intent(in) :: block
    integer, intent(in) :: i, j, k
    real(rk) :: x(3, 8)
    x(:, 1) = block%x(:, i, j, k)
    x(:, 2) = block%x(:, i + 1, j, k)
    x(:, 3) = block%x(:, i + 1, j + 1, k)
    x(:, 4) = block%x(:, i, j + 1, k)
    x(:, 5) = block%x(:, i, j, k + 1)
    x(:, 6) = block%x(:, i + 1, j, k + 1)
    x(:, 7) = block%x(:, i + 1, j + 1, k + 1)
    x(:, 8) = block%x(:, i, j + 1, k + 1)
  end function block_hex

  !> Mirror a left-handed block in i so that its hexes have positive volume.
  subroutine block_orient(block)
    type(block_t), intent(inout) :: block
    real(rk), allocatable :: mirrored(:, :, :, :)
    integer :: swap, i
    if (hex_volume(block_hex(block, 0, 0, 0)) >= 0.0_rk) return
    allocate(mirrored(3, 0:block%n(1), 0:block%n(2), 0:block%n(3)))
    do i = 0, block%n(1)
      mirrored(:, i, :, :) = block%x(:, block%n(1) - i, :, :)
    end do
    call move_alloc(mirrored, block%x)
    swap = block%face_set(4)
    block%face_set(4) = block%face_set(6)
    block%face_set(6) = swap
  end subroutine block_orient

  !> Build the global mesh from blocks: orient, merge shared nodes, connect, collect sets.
  subroutine assemble(blocks, names, length_scale, mesh)
    type(block_t), intent(inout) :: blocks(:)
    character(len=*), intent(in) :: names(:) !< set names, indexed by face_set
    real(rk), intent(in) :: length_scale !< body size, for the merge tolerance
    type(global_mesh_t), intent(inout) :: mesh
    real(rk), allocatable :: raw(:, :)
    integer, allocatable :: node_offset(:), zone_offset(:), new_id(:)
    integer :: b, nraw, i, j, k, z, s, f, n(3), pass, count_face

    do b = 1, size(blocks)
      call block_orient(blocks(b))
    end do
    allocate(node_offset(size(blocks)), zone_offset(size(blocks)))
    nraw = 0
    mesh%nzone = 0
    do b = 1, size(blocks)
      node_offset(b) = nraw
      zone_offset(b) = mesh%nzone
      nraw = nraw + product(blocks(b)%n + 1)
      mesh%nzone = mesh%nzone + product(blocks(b)%n)
    end do
    allocate(raw(3, nraw))
    do b = 1, size(blocks)
      raw(:, node_offset(b) + 1:node_offset(b) + product(blocks(b)%n + 1)) = &
          reshape(blocks(b)%x, [3, product(blocks(b)%n + 1)])
    end do
    call merge_nodes(raw, MERGE_TOLERANCE * length_scale, new_id, mesh%coordinates, mesh%nnode)

    allocate(mesh%connectivity(8, mesh%nzone), mesh%zone_block(mesh%nzone))
    mesh%zone_block = 0
    do b = 1, size(blocks)
      n = blocks(b)%n
      do k = 0, n(3) - 1
        do j = 0, n(2) - 1
          do i = 0, n(1) - 1
            z = zone_offset(b) + 1 + i + n(1) * (j + n(2) * k)
            mesh%connectivity(:, z) = int([raw_id(i, j, k), raw_id(i + 1, j, k), &
                raw_id(i + 1, j + 1, k), raw_id(i, j + 1, k), raw_id(i, j, k + 1), &
                raw_id(i + 1, j, k + 1), raw_id(i + 1, j + 1, k + 1), raw_id(i, j + 1, k + 1)], ik)
          end do
        end do
      end do
    end do

    ! Sets: count in the first pass, fill in the second.
    mesh%nset = size(names)
    allocate(mesh%set_name(mesh%nset), mesh%set_start(mesh%nset + 1))
    mesh%set_name = names
    do pass = 1, 2
      count_face = 0
      mesh%set_start(1) = 1
      do s = 1, mesh%nset
        do b = 1, size(blocks)
          n = blocks(b)%n
          do f = 1, 6
            if (blocks(b)%face_set(f) /= s) cycle
            do k = 0, n(3) - 1
              do j = 0, n(2) - 1
                do i = 0, n(1) - 1
                  if (.not. on_face(f, i, j, k, n)) cycle
                  count_face = count_face + 1
                  if (pass == 2) then
                    mesh%set_zone(count_face) = int(zone_offset(b) + 1 + i + n(1) * (j &
                        + n(2) * k), ik)
                    mesh%set_face(count_face) = int(f, ik)
                  end if
                end do
              end do
            end do
          end do
        end do
        mesh%set_start(s + 1) = count_face + 1
      end do
      if (pass == 1) allocate(mesh%set_zone(count_face), mesh%set_face(count_face))
    end do

  contains

    !> Merged id of node (ii, jj, kk) of block b.
    integer function raw_id(ii, jj, kk)
      integer, intent(in) :: ii, jj, kk
      raw_id = new_id(node_offset(b) + 1 + ii + (n(1) + 1) * (jj + (n(2) + 1) * kk))
    end function raw_id

  end subroutine assemble

  !> True when hex (i, j, k) of a block with n zones has face f on the block surface.
  pure logical function on_face(f, i, j, k, n)
    integer, intent(in) :: f, i, j, k, n(3)
    select case (f)
    case (1)
      on_face = k == 0
    case (2)
      on_face = k == n(3) - 1
    case (3)
      on_face = j == 0
    case (4)
      on_face = i == n(1) - 1
    case (5)
      on_face = j == n(2) - 1
    case default
      on_face = i == 0
    end select
  end function on_face

  !> Merge points closer than tolerance: new_id maps every raw point to its
  !> node, numbered in order of first appearance; coordinates are the nodes'.
  subroutine merge_nodes(raw, tolerance, new_id, coordinates, nnode)
    real(rk), intent(in) :: raw(:, :) !< (3, npoint)
    real(rk), intent(in) :: tolerance
    integer, allocatable, intent(out) :: new_id(:)
    real(rk), allocatable, intent(out) :: coordinates(:, :)
    integer, intent(out) :: nnode
    ! A direction along no mesh line, so few points share a key.
    real(rk), parameter :: DIRECTION(3) = [0.8017_rk, 0.5323_rk, 0.2719_rk]
    real(rk), allocatable :: key(:)
    integer, allocatable :: order(:), representative(:)
    real(rk) :: window
    integer :: npoint, a, c, p, q

    npoint = size(raw, 2)
    key = matmul(DIRECTION, raw)
    call sort_order(key, order)
    window = tolerance * norm2(DIRECTION)
    allocate(representative(npoint))
    representative = 0
    do a = 1, npoint
      p = order(a)
      if (representative(p) /= 0) cycle
      representative(p) = p
      do c = a + 1, npoint
        q = order(c)
        if (key(q) - key(p) > window) exit
        if (representative(q) == 0) then
          if (norm2(raw(:, q) - raw(:, p)) <= tolerance) representative(q) = p
        end if
      end do
    end do
    allocate(new_id(npoint), coordinates(3, npoint))
    new_id = 0
    nnode = 0
    do p = 1, npoint
      q = representative(p)
      if (new_id(q) == 0) then
        nnode = nnode + 1
        new_id(q) = nnode
        coordinates(:, nnode) = raw(:, q)
      end if
      new_id(p) = new_id(q)
    end do
    coordinates = coordinates(:, 1:nnode)
  end subroutine merge_nodes

  !> (cos, sin) of the angle (pi/2) quarters j / n, exact at multiples of pi/2.
  pure function circle_point(j, n, quarters) result(c)
    integer, intent(in) :: j, n, quarters
    real(rk) :: c(2)
    integer :: m, whole
    m = j * quarters
    whole = m / n
    c = [cos(0.5_rk * PI * real(m - whole * n, rk) / real(n, rk)), &
        sin(0.5_rk * PI * real(m - whole * n, rk) / real(n, rk))]
    c = rotate_quarters(c, whole)
  end function circle_point

  !> Rotate a point of the plane by q quarter turns counter-clockwise (exact).
  pure function rotate_quarters(p, q) result(r)
    real(rk), intent(in) :: p(2)
    integer, intent(in) :: q
    real(rk) :: r(2)
    select case (modulo(q, 4))
    case (0)
      r = p
    case (1)
      r = [-p(2), p(1)]
    case (2)
      r = [-p(1), -p(2)]
    case default
      r = [p(2), -p(1)]
    end select
  end function rotate_quarters

  pure function cross(a, b) result(c)
    real(rk), intent(in) :: a(3), b(3)
    real(rk) :: c(3)
    c = [a(2) * b(3) - a(3) * b(2), a(3) * b(1) - a(1) * b(3), a(1) * b(2) - a(2) * b(1)]
  end function cross

  !> Record text as a problem unless condition holds.
  subroutine require(status, condition, text)
    type(status_t), intent(inout) :: status
    logical, intent(in) :: condition
    character(len=*), intent(in) :: text
    if (.not. condition) call status%add(text)
  end subroutine require

  !> A zone count must be at least least.
  subroutine require_count(status, key, value, least)
    type(status_t), intent(inout) :: status
    character(len=*), intent(in) :: key !< 'generator: component'
    integer, intent(in) :: value, least
    if (value < least) call status%add(key // ' must be >= ' // int_text(least) // ' (got ' // &
        int_text(value) // ')')
  end subroutine require_count

end module mesh_curved
