!> Hex meshes of curved bodies without degenerate zones: a solid rod (O-grid),
!> a thick tube, a spherical shell octant (cubed-sphere patches), a ball octant
!> (cube core and three patches out to the sphere) and the octant of a box
!> minus a ball (three patches from the sphere out to the box faces).
!>
!> Each body is a part of structured blocks (logical i, j, k; mesh_blocks):
!> each block's node positions come from a point function, so a rank builds
!> only the zones of its range (range_add_part), and the whole body is built
!> only for tests (mesh_make_*). Nodes that blocks share are merged by
!> position (within 1e-10 of the body size; shared nodes are computed by the
!> same formulas, so they agree to round-off); nodes are numbered in order of
!> first appearance and zones block by block, i fastest. Nodes on a circle or
!> sphere are computed as radius times a unit direction, and nodes on a
!> symmetry plane have that coordinate exactly zero. Balls and shells come
!> as an octant, a quarter (x, y >= 0), a half (y >= 0) or a whole sphere:
!> the octant and its mirror images, the octant first (so it keeps its
!> numbering). zone_block is left 0: the caller assigns blocks.
module mesh_curved
  use core_kinds, only: rk, ik
  use core_status, only: status_t
  use core_text, only: real_text => to_text, int_text => to_text
  use mesh_blocks, only: block_part_t, part_prepare, part_assemble
  use mesh_global, only: global_mesh_t, interval_points, NAME_LEN
  implicit none
  private
  public :: rod_spec_t, tube_spec_t, shell_spec_t, ball_spec_t, box_minus_ball_spec_t
  public :: mesh_make_rod, mesh_make_tube, mesh_make_shell, mesh_make_ball
  public :: mesh_make_box_minus_ball, curved_part, sector_known

  real(rk), parameter :: PI = acos(-1.0_rk)
  !> Angle between a bulged core edge and the straight one at the core corner:
  !> 15 degrees makes all three zones meeting at that corner 120 degrees wide.
  real(rk), parameter :: CORE_BULGE = PI / 12.0_rk
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

  !> Spherical shell between ri and ro, centred at 0: the octant (x, y, z >=
  !> 0), a quarter (x, y >= 0), a half (y >= 0) or the whole ('full').
  type :: shell_spec_t
    real(rk) :: ri = 8.0_rk !< inner radius
    real(rk) :: ro = 10.0_rk !< outer radius
    integer :: n_patch = 10 !< zones along each edge of the three surface patches
    integer :: n_radial = 8 !< zones from ri to ro
    real(rk) :: radial_ratio = 1.0_rk !< last/first zone thickness (outward)
    character(len=16) :: sector = 'octant' !< 'octant', 'quarter', 'half' or 'full'
  end type shell_spec_t

  !> Ball of radius R centred at 0, octant (x, y, z >= 0), quarter (x, y >=
  !> 0), half (y >= 0) or whole ('full'). The octant is a cube core [0, a]^3
  !> and three patches, each joining one outer core face to the sphere by
  !> straight lines (the 3D analogue of the rod's O-grid).
  type :: ball_spec_t
    real(rk) :: radius = 0.5_rk !< R
    integer :: n_core = 8 !< zones along each core edge (and each patch edge on the sphere)
    integer :: n_radial = 6 !< zones from the core face to the sphere
    real(rk) :: radial_ratio = 1.0_rk !< last/first zone thickness (outward)
    real(rk) :: core_fraction = 0.45_rk !< a = f R, 0.2 <= f <= 0.5
    character(len=16) :: sector = 'octant' !< 'octant', 'quarter', 'half' or 'full'
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

  !> The generators as parts of blocks (mesh_blocks), with what their point
  !> functions need.
  type, extends(block_part_t) :: rod_part_t
    integer :: nc = 0, nr = 0
    real(rk) :: radius = 0.0_rk, a = 0.0_rk, rho = 0.0_rk, xc = 0.0_rk, b = 0.0_rk
    real(rk), allocatable :: z(:) !< (0:n_axial)
  contains
    procedure :: raw_point => rod_point
  end type rod_part_t

  type, extends(block_part_t) :: tube_part_t
    integer :: n_theta = 0, quarters = 0
    real(rk) :: e1(3) = 0.0_rk, e2(3) = 0.0_rk, axis(3) = 0.0_rk, origin(3) = 0.0_rk
    real(rk), allocatable :: r(:), z(:) !< (0:n_radial), (0:n_axial)
  contains
    procedure :: raw_point => tube_point
  end type tube_part_t

  type, extends(block_part_t) :: shell_part_t
    real(rk), allocatable :: r(:), t(:) !< (0:n_radial), (0:n_patch)
    real(rk), allocatable :: signs(:, :) !< (3, copies) each octant copy's signs
  contains
    procedure :: raw_point => shell_point
  end type shell_part_t

  type, extends(block_part_t) :: ball_part_t
    integer :: nr = 0
    real(rk) :: radius = 0.0_rk, a = 0.0_rk
    real(rk), allocatable :: s(:), t(:), cc(:) !< (0:n_radial), (0:n_core), (0:n_core)
    real(rk), allocatable :: signs(:, :) !< (3, copies)
  contains
    procedure :: raw_point => ball_point
  end type ball_part_t

  type, extends(block_part_t) :: box_minus_ball_part_t
    integer :: nr = 0
    real(rk) :: radius = 0.0_rk, length = 0.0_rk
    real(rk), allocatable :: s(:), t(:) !< (0:n_radial), (0:n_patch)
  contains
    procedure :: raw_point => box_minus_ball_point
  end type box_minus_ball_part_t

contains

  ! ------------------------------------------------------------ point functions

  !> Rod: block 3 q + 1 the core of quarter q (i along x, j along y), 3 q + 2
  !> the ring below the diagonal (i radial, core to circle; j counter-
  !> clockwise), 3 q + 3 its mirror image in x = y.
  pure function rod_point(this, b, i, j, k) result(x)
    class(rod_part_t), intent(in) :: this
    integer, intent(in) :: b, i, j, k
    real(rk) :: x(3), p(2), u, v
    integer :: q
    q = (b - 1) / 3
    v = real(j, rk) / real(this%nc, rk)
    select case (mod(b - 1, 3))
    case (0)
      u = real(i, rk) / real(this%nc, rk)
      p = rotate_quarters(rod_core_point(this, u, v), q)
      x = [p, this%z(k)]
    case (1)
      u = real(i, rk) / real(this%nr, rk)
      p = rod_ring_point(this, u, v)
      x = [rotate_quarters(p, q), this%z(k)]
    case default
      u = real(i, rk) / real(this%nr, rk)
      p = rod_ring_point(this, u, v)
      x = [rotate_quarters([p(2), p(1)], q), this%z(k)]
    end select
  end function rod_point

  !> Point s (0..1) of the rod's bulged core edge, from (b, 0) to (a, a).
  pure function rod_core_edge(this, s) result(pt)
    type(rod_part_t), intent(in) :: this
    real(rk), intent(in) :: s
    real(rk) :: pt(2)
    pt = [this%xc + this%rho * cos(s * CORE_BULGE), this%rho * sin(s * CORE_BULGE)]
  end function rod_core_edge

  !> Rod core point (u, v) in [0,1]^2: transfinite (Coons) interpolation of
  !> the straight edges on the axes and the two bulged edges.
  pure function rod_core_point(this, uu, vv) result(pt)
    type(rod_part_t), intent(in) :: this
    real(rk), intent(in) :: uu, vv
    real(rk) :: pt(2), right(2), upper(2)
    right = rod_core_edge(this, vv)
    upper = rod_core_edge(this, uu)
    upper = [upper(2), upper(1)]
    pt = (1.0_rk - vv) * [uu * this%b, 0.0_rk] + vv * upper + (1.0_rk - uu) * &
        [0.0_rk, vv * this%b] + uu * right - (uu * (1.0_rk - vv) * [this%b, 0.0_rk] + &
        (1.0_rk - uu) * vv * [0.0_rk, this%b] + uu * vv * [this%a, this%a])
  end function rod_core_point

  !> Rod ring point: fraction t of the straight way from the core edge point
  !> s to the circle at angle s pi/4 (t = 1 gives the circle point exactly).
  pure function rod_ring_point(this, t, s) result(pt)
    type(rod_part_t), intent(in) :: this
    real(rk), intent(in) :: t, s
    real(rk) :: pt(2)
    pt = (1.0_rk - t) * rod_core_edge(this, s) + t * (this%radius * [cos(s * 0.25_rk * PI), &
        sin(s * 0.25_rk * PI)])
  end function rod_ring_point

  !> Tube: one block (b = 1), i radial, j around, k along the axis.
  pure function tube_point(this, b, i, j, k) result(x)
    class(tube_part_t), intent(in) :: this
    integer, intent(in) :: b, i, j, k
    real(rk) :: x(3), c(2)
    c = circle_point(j, this%n_theta, this%quarters)
    x = this%origin + (this%r(i) * c(1)) * this%e1 + (this%r(i) * c(2)) * this%e2 &
        + this%z(k) * this%axis
  end function tube_point

  !> Shell: octant copy c = (b - 1) / 3 + 1, patch mod(b - 1, 3) + 1 (i, j
  !> the patch angles, k radial), mirrored by the copy's signs.
  pure function shell_point(this, b, i, j, k) result(x)
    class(shell_part_t), intent(in) :: this
    integer, intent(in) :: b, i, j, k
    real(rk) :: x(3), d(3, 3)
    integer :: patch
    patch = mod(b - 1, 3) + 1
    d = patch_directions(this%t(i), this%t(j))
    d(:, patch) = d(:, patch) / sqrt(sum(d(:, patch)**2))
    x = this%r(k) * d(:, patch)
    x = x * this%signs(:, (b - 1) / 3 + 1)
  end function shell_point

  !> Ball: octant copy c = (b - 1) / 4 + 1; block mod(b - 1, 4) + 1 is the
  !> core (1) or the patch on the core face x = a (2), y = a (3), z = a (4),
  !> i, j across the core face and k from it to the sphere.
  pure function ball_point(this, b, i, j, k) result(x)
    class(ball_part_t), intent(in) :: this
    integer, intent(in) :: b, i, j, k
    real(rk) :: x(3), d(3, 3), core(3, 3), across, a
    integer :: patch
    a = this%a
    patch = mod(b - 1, 4)
    if (patch == 0) then
      x = a * [this%cc(i), this%cc(j), this%cc(k)]
    else
      d = patch_directions(this%t(i), this%t(j))
      across = a * this%cc(i)
      core(:, 1) = [a, across, a * this%cc(j)]
      core(:, 2) = [across, a, a * this%cc(j)]
      core(:, 3) = [across, a * this%cc(j), a]
      d(:, patch) = this%radius * d(:, patch) / sqrt(sum(d(:, patch)**2))
      if (k == this%nr) then
        ! The sphere node exactly radius times the unit direction.
        x = d(:, patch)
      else
        x = (1.0_rk - this%s(k)) * core(:, patch) + this%s(k) * d(:, patch)
      end if
    end if
    x = x * this%signs(:, (b - 1) / 4 + 1)
  end function ball_point

  !> Box minus ball: patch b (i, j the patch angles, k along the ray from
  !> the sphere to the box face).
  pure function box_minus_ball_point(this, b, i, j, k) result(x)
    class(box_minus_ball_part_t), intent(in) :: this
    integer, intent(in) :: b, i, j, k
    real(rk) :: x(3), d(3, 3), sphere(3)
    d = patch_directions(this%t(i), this%t(j))
    sphere = this%radius * d(:, b) / sqrt(sum(d(:, b)**2))
    if (k == 0) then
      x = sphere
    else if (k == this%nr) then
      x = this%length * d(:, b)
    else
      x = (1.0_rk - this%s(k)) * sphere + this%s(k) * this%length * d(:, b)
    end if
  end function box_minus_ball_point

  ! ------------------------------------------------------------- the parts

  !> A part's blocks: n zones and face sets of each.
  subroutine set_blocks(part, n, face_set, names, length_scale)
    class(block_part_t), intent(inout) :: part
    integer, intent(in) :: n(:, :), face_set(:, :)
    character(len=*), intent(in) :: names(:)
    real(rk), intent(in) :: length_scale
    part%nblock = size(n, 2)
    part%n = n
    part%face_set = face_set
    allocate(part%set_names(size(names)))
    part%set_names = names
    part%length_scale = length_scale
  end subroutine set_blocks

  !> The generator of a deck's curved part as blocks, numbered
  !> (part_prepare); problems go to status and leave part unallocated.
  subroutine curved_part(kind, rod, tube, shell, ball, box_minus_ball, part, status)
    character(len=*), intent(in) :: kind !< 'rod', 'tube', 'shell', 'ball', 'box_minus_ball'
    type(rod_spec_t), intent(in) :: rod
    type(tube_spec_t), intent(in) :: tube
    type(shell_spec_t), intent(in) :: shell
    type(ball_spec_t), intent(in) :: ball
    type(box_minus_ball_spec_t), intent(in) :: box_minus_ball
    class(block_part_t), allocatable, intent(out) :: part
    type(status_t), intent(inout) :: status
    select case (kind)
    case ('rod')
      call rod_part(rod, part, status)
    case ('tube')
      call tube_part(tube, part, status)
    case ('shell')
      call shell_part(shell, part, status)
    case ('ball')
      call ball_part(ball, part, status)
    case default
      call box_minus_ball_part(box_minus_ball, part, status)
    end select
    if (allocated(part)) call part_prepare(part)
  end subroutine curved_part

  !> Solid rod along z. Quarter: one core block and two ring blocks (the ring
  !> split on the 45 degree diagonal); full: the quarter rotated four times.
  !> Sets: side, bottom, top (+ xsym, ysym for the quarter).
  subroutine rod_part(spec, part, status)
    type(rod_spec_t), intent(in) :: spec
    class(block_part_t), allocatable, intent(out) :: part
    type(status_t), intent(inout) :: status
    integer, parameter :: SIDE = 1, BOTTOM = 2, TOP = 3, XSYM = 4, YSYM = 5
    type(rod_part_t), allocatable :: rod
    integer, allocatable :: n(:, :), face_set(:, :)
    integer :: nerr, nq, q, nc, nr, nz, xset, yset
    logical :: full

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

    allocate(rod)
    full = spec%sector == 'full'
    nc = spec%n_core
    nr = spec%n_radial
    nz = spec%n_axial
    rod%nc = nc
    rod%nr = nr
    rod%radius = spec%radius
    call interval_points(1, [spec%z0, spec%z0 + spec%length], [nz], [spec%axial_ratio], rod%z)
    ! Core edge x = a bulged into an arc of radius rho centred at (xc, 0): from
    ! (b, 0) on the x axis to the core corner (a, a).
    rod%a = spec%core_fraction * spec%radius
    rod%rho = rod%a / sin(CORE_BULGE)
    rod%xc = rod%a - rod%rho * cos(CORE_BULGE)
    rod%b = rod%xc + rod%rho
    xset = XSYM
    yset = YSYM
    nq = 1
    if (full) then
      xset = 0
      yset = 0
      nq = 4
    end if
    allocate(n(3, 3 * nq), face_set(6, 3 * nq))
    do q = 0, nq - 1
      n(:, 3 * q + 1) = [nc, nc, nz]
      face_set(:, 3 * q + 1) = [BOTTOM, TOP, yset, 0, 0, xset]
      n(:, 3 * q + 2) = [nr, nc, nz]
      face_set(:, 3 * q + 2) = [BOTTOM, TOP, yset, SIDE, 0, 0]
      n(:, 3 * q + 3) = [nr, nc, nz]
      face_set(:, 3 * q + 3) = [BOTTOM, TOP, xset, SIDE, 0, 0]
    end do
    if (full) then
      call set_blocks(rod, n, face_set, [character(len=NAME_LEN) :: 'side', 'bottom', 'top'], &
          max(spec%radius, spec%length))
    else
      call set_blocks(rod, n, face_set, [character(len=NAME_LEN) :: 'side', 'bottom', 'top', &
          'xsym', 'ysym'], max(spec%radius, spec%length))
    end if
    call move_alloc(rod, part)
  end subroutine rod_part

  !> Thick tube: one block, i radial, j around, k along the axis; a full tube
  !> closes on itself at theta = 0. Sets: inner, outer, bottom, top, and the
  !> cut planes (half: ysym for both cuts; quarter: ysym at theta = 0 and xsym
  !> at theta = 90 degrees; local axes, i.e. the global x, y planes by default).
  subroutine tube_part(spec, part, status)
    type(tube_spec_t), intent(in) :: spec
    class(block_part_t), allocatable, intent(out) :: part
    type(status_t), intent(inout) :: status
    integer, parameter :: INNER = 1, OUTER = 2, BOTTOM = 3, TOP = 4
    type(tube_part_t), allocatable :: tube
    real(rk) :: axis(3), e1(3), length_axis, projected
    integer :: nerr, quarters, min_theta, start_set, end_set
    character(len=NAME_LEN), allocatable :: names(:)

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

    allocate(tube)
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
    tube%e1 = e1
    tube%e2 = cross(axis, e1)
    tube%axis = axis
    tube%origin = spec%origin
    tube%quarters = quarters
    tube%n_theta = spec%n_theta

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
    call interval_points(1, [spec%ri, spec%ro], [spec%n_radial], [1.0_rk], tube%r)
    call interval_points(1, [0.0_rk, spec%length], [spec%n_axial], [spec%axial_ratio], tube%z)
    call set_blocks(tube, reshape([spec%n_radial, spec%n_theta, spec%n_axial], [3, 1]), &
        reshape([BOTTOM, TOP, start_set, OUTER, end_set, INNER], [6, 1]), names, &
        max(spec%ro, spec%length, maxval(abs(spec%origin))))
    call move_alloc(tube, part)
  end subroutine tube_part

  !> The octant copies of a sphere sector ('octant': x, y, z >= 0;
  !> 'quarter': x, y >= 0; 'half': y >= 0; 'full'), each as the signs of
  !> its coordinates, the octant first; keep(a): the plane normal to axis a
  !> stays a boundary (no copy across it).
  subroutine sector_signs(sector, signs, keep)
    character(len=*), intent(in) :: sector
    real(rk), allocatable, intent(out) :: signs(:, :)
    logical, intent(out) :: keep(3)
    real(rk), parameter :: P = 1.0_rk, M = -1.0_rk
    select case (sector)
    case ('quarter')
      signs = reshape([P, P, P, P, P, M], [3, 2])
      keep = [.true., .true., .false.]
    case ('half')
      signs = reshape([P, P, P, P, P, M, M, P, P, M, P, M], [3, 4])
      keep = [.false., .true., .false.]
    case ('full')
      signs = reshape([P, P, P, P, P, M, M, P, P, M, P, M, P, M, P, P, M, M, M, M, P, &
          M, M, M], [3, 8])
      keep = .false.
    case default
      signs = reshape([P, P, P], [3, 1])
      keep = .true.
    end select
  end subroutine sector_signs

  !> Whether a sector name is known ('octant', 'quarter', 'half', 'full').
  pure logical function sector_known(sector)
    character(len=*), intent(in) :: sector
    sector_known = sector == 'octant' .or. sector == 'quarter' .or. sector == 'half' .or. &
        sector == 'full'
  end function sector_known

  !> The octant's blocks repeated for each copy of the sector, with the
  !> sets of planes that copies join removed; planes(a): the octant's set
  !> on the plane normal to axis a. names: the octant's set names, those
  !> kept come out in their order.
  subroutine sector_blocks(n8, sets8, names8, planes, sector, n, face_set, names, signs)
    integer, intent(in) :: n8(:, :), sets8(:, :) !< the octant's blocks
    character(len=*), intent(in) :: names8(:)
    integer, intent(in) :: planes(3)
    character(len=*), intent(in) :: sector
    integer, allocatable, intent(out) :: n(:, :), face_set(:, :)
    character(len=NAME_LEN), allocatable, intent(out) :: names(:)
    real(rk), allocatable, intent(out) :: signs(:, :)
    logical :: keep(3), kept(size(names8))
    integer :: map(0:size(names8)), c, b, s, a, nb
    call sector_signs(sector, signs, keep)
    kept = .true.
    do a = 1, 3
      if (.not. keep(a)) kept(planes(a)) = .false.
    end do
    map = 0
    allocate(names(0))
    do s = 1, size(names8)
      if (.not. kept(s)) cycle
      names = [character(len=NAME_LEN) :: names, names8(s)]
      map(s) = size(names)
    end do
    nb = size(n8, 2)
    allocate(n(3, nb * size(signs, 2)), face_set(6, nb * size(signs, 2)))
    do c = 1, size(signs, 2)
      do b = 1, nb
        n(:, (c - 1) * nb + b) = n8(:, b)
        face_set(:, (c - 1) * nb + b) = map(sets8(:, b))
      end do
    end do
  end subroutine sector_blocks

  !> Spherical shell: the octant's three cubed-sphere patches (equiangular
  !> gnomonic, one around each axis) meeting at the (1,1,1) direction; i, j
  !> the two patch angles, k radial; the other octants of the sector are its
  !> mirror images. Sets: inner, outer, and xsym, ysym, zsym where the sector
  !> ends on that plane.
  subroutine shell_part(spec, part, status)
    type(shell_spec_t), intent(in) :: spec
    class(block_part_t), allocatable, intent(out) :: part
    type(status_t), intent(inout) :: status
    integer, parameter :: INNER = 1, OUTER = 2, XSYM = 3, YSYM = 4, ZSYM = 5
    type(shell_part_t), allocatable :: shell
    integer, allocatable :: n(:, :), face_set(:, :)
    character(len=NAME_LEN), allocatable :: names(:)
    integer :: nerr, np, nr

    nerr = status%count
    call require(status, spec%ri > 0.0_rk, 'shell: ri must be > 0 (got ' // &
        real_text(spec%ri) // ')')
    call require(status, spec%ro > spec%ri, 'shell: ro must be > ri (got ri = ' // &
        real_text(spec%ri) // ', ro = ' // real_text(spec%ro) // ')')
    call require_count(status, 'shell: n_patch', spec%n_patch, 1)
    call require_count(status, 'shell: n_radial', spec%n_radial, 1)
    call require(status, spec%radial_ratio > 0.0_rk, 'shell: radial_ratio must be > 0 (got ' &
        // real_text(spec%radial_ratio) // ')')
    call require(status, sector_known(spec%sector), "shell: sector must be 'octant', " // &
        "'quarter', 'half' or 'full' (got '" // trim(spec%sector) // "')")
    if (status%count > nerr) return

    allocate(shell)
    np = spec%n_patch
    nr = spec%n_radial
    call interval_points(1, [spec%ri, spec%ro], [nr], [spec%radial_ratio], shell%r)
    ! Tangents of the equiangular patch coordinates, exact at 0 and 1.
    call patch_tangents(np, shell%t)
    ! Patch 1 around x: (1, tan i, tan j); 2 around y: (tan i, 1, tan j);
    ! 3 around z: (tan i, tan j, 1).
    call sector_blocks(reshape([np, np, nr, np, np, nr, np, np, nr], [3, 3]), &
        reshape([INNER, OUTER, ZSYM, 0, 0, YSYM, INNER, OUTER, ZSYM, 0, 0, XSYM, &
        INNER, OUTER, YSYM, 0, 0, XSYM], [6, 3]), [character(len=NAME_LEN) :: 'inner', &
        'outer', 'xsym', 'ysym', 'zsym'], [XSYM, YSYM, ZSYM], spec%sector, n, face_set, &
        names, shell%signs)
    call set_blocks(shell, n, face_set, names, spec%ro)
    call move_alloc(shell, part)
  end subroutine shell_part

  !> Ball: the octant's core block (i, j, k along x, y, z) and three patches
  !> (i, j across the core face, k from the core face to the sphere; patch 1
  !> on the face x = a, 2 on y = a, 3 on z = a); the other octants of the
  !> sector are its mirror images. The sphere nodes are equiangular
  !> cubed-sphere points, radius times a unit direction. Sets: outer (the
  !> sphere), and xmin, ymin, zmin where the sector ends on that plane.
  subroutine ball_part(spec, part, status)
    type(ball_spec_t), intent(in) :: spec
    class(block_part_t), allocatable, intent(out) :: part
    type(status_t), intent(inout) :: status
    integer, parameter :: OUTER = 1, XMIN = 2, YMIN = 3, ZMIN = 4
    type(ball_part_t), allocatable :: ball
    integer, allocatable :: n(:, :), face_set(:, :)
    character(len=NAME_LEN), allocatable :: names(:)
    integer :: nerr, nc, nr, i

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
    call require(status, sector_known(spec%sector), "ball: sector must be 'octant', " // &
        "'quarter', 'half' or 'full' (got '" // trim(spec%sector) // "')")
    if (status%count > nerr) return

    allocate(ball)
    nc = spec%n_core
    nr = spec%n_radial
    ball%nr = nr
    ball%radius = spec%radius
    ball%a = spec%core_fraction * spec%radius
    call interval_points(1, [0.0_rk, 1.0_rk], [nr], [spec%radial_ratio], ball%s)
    ball%s(0) = 0.0_rk
    ball%s(nr) = 1.0_rk
    call patch_tangents(nc, ball%t)
    ! Core node coordinate i / nc, exactly 0 and 1 at the ends.
    allocate(ball%cc(0:nc))
    do i = 0, nc
      ball%cc(i) = real(i, rk) / real(nc, rk)
    end do
    call sector_blocks(reshape([nc, nc, nc, nc, nc, nr, nc, nc, nr, nc, nc, nr], [3, 4]), &
        reshape([ZMIN, 0, YMIN, 0, 0, XMIN, 0, OUTER, ZMIN, 0, 0, YMIN, &
        0, OUTER, ZMIN, 0, 0, XMIN, 0, OUTER, YMIN, 0, 0, XMIN], [6, 4]), &
        [character(len=NAME_LEN) :: 'outer', 'xmin', 'ymin', 'zmin'], [XMIN, YMIN, ZMIN], &
        spec%sector, n, face_set, names, ball%signs)
    call set_blocks(ball, n, face_set, names, spec%radius)
    call move_alloc(ball, part)
  end subroutine ball_part

  !> Box minus ball octant: three patches (i, j the equiangular patch angles,
  !> k along the ray from the sphere to the box face; patch 1 ends on x = L,
  !> 2 on y = L, 3 on z = L). Node (i, j, k) lies on the ray through the
  !> cubed-sphere direction (i, j); the sphere nodes are radius times the unit
  !> direction, the box nodes L (1, tan, tan) (the face coordinate exactly L).
  !> Sets: inner (the sphere), xmin, ymin, zmin, xmax, ymax, zmax.
  subroutine box_minus_ball_part(spec, part, status)
    type(box_minus_ball_spec_t), intent(in) :: spec
    class(block_part_t), allocatable, intent(out) :: part
    type(status_t), intent(inout) :: status
    integer, parameter :: INNER = 1, XMIN = 2, YMIN = 3, ZMIN = 4, XMAX = 5, YMAX = 6, ZMAX = 7
    type(box_minus_ball_part_t), allocatable :: bmb
    integer :: nerr, np, nr

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

    allocate(bmb)
    np = spec%n_patch
    nr = spec%n_radial
    bmb%nr = nr
    bmb%radius = spec%radius
    bmb%length = spec%length
    call interval_points(1, [0.0_rk, 1.0_rk], [nr], [spec%radial_ratio], bmb%s)
    bmb%s(0) = 0.0_rk
    bmb%s(nr) = 1.0_rk
    call patch_tangents(np, bmb%t)
    call set_blocks(bmb, reshape([np, np, nr, np, np, nr, np, np, nr], [3, 3]), &
        reshape([INNER, XMAX, ZMIN, 0, 0, YMIN, INNER, YMAX, ZMIN, 0, 0, XMIN, &
        INNER, ZMAX, YMIN, 0, 0, XMIN], [6, 3]), [character(len=NAME_LEN) :: 'inner', 'xmin', &
        'ymin', 'zmin', 'xmax', 'ymax', 'zmax'], spec%length)
    call move_alloc(bmb, part)
  end subroutine box_minus_ball_part

  ! ------------------------------------------ whole parts (tests and tools)

  !> The whole part of a generator as a global mesh (part_assemble).
  subroutine whole_part(part, mesh)
    class(block_part_t), allocatable, intent(inout) :: part
    type(global_mesh_t), intent(inout) :: mesh
    call mesh%free()
    if (.not. allocated(part)) return
    call part_prepare(part)
    call part_assemble(part, mesh)
  end subroutine whole_part

  !> Solid rod along z, whole (rod_part).
  subroutine mesh_make_rod(spec, mesh, status)
    type(rod_spec_t), intent(in) :: spec
    type(global_mesh_t), intent(inout) :: mesh
    type(status_t), intent(inout) :: status
    class(block_part_t), allocatable :: part
    call rod_part(spec, part, status)
    call whole_part(part, mesh)
  end subroutine mesh_make_rod

  !> Thick tube, whole (tube_part).
  subroutine mesh_make_tube(spec, mesh, status)
    type(tube_spec_t), intent(in) :: spec
    type(global_mesh_t), intent(inout) :: mesh
    type(status_t), intent(inout) :: status
    class(block_part_t), allocatable :: part
    call tube_part(spec, part, status)
    call whole_part(part, mesh)
  end subroutine mesh_make_tube

  !> Spherical shell, whole (shell_part).
  subroutine mesh_make_shell(spec, mesh, status)
    type(shell_spec_t), intent(in) :: spec
    type(global_mesh_t), intent(inout) :: mesh
    type(status_t), intent(inout) :: status
    class(block_part_t), allocatable :: part
    call shell_part(spec, part, status)
    call whole_part(part, mesh)
  end subroutine mesh_make_shell

  !> Ball, whole (ball_part).
  subroutine mesh_make_ball(spec, mesh, status)
    type(ball_spec_t), intent(in) :: spec
    type(global_mesh_t), intent(inout) :: mesh
    type(status_t), intent(inout) :: status
    class(block_part_t), allocatable :: part
    call ball_part(spec, part, status)
    call whole_part(part, mesh)
  end subroutine mesh_make_ball

  !> Box minus ball octant, whole (box_minus_ball_part).
  subroutine mesh_make_box_minus_ball(spec, mesh, status)
    type(box_minus_ball_spec_t), intent(in) :: spec
    type(global_mesh_t), intent(inout) :: mesh
    type(status_t), intent(inout) :: status
    class(block_part_t), allocatable :: part
    call box_minus_ball_part(spec, part, status)
    call whole_part(part, mesh)
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
