!> Curved-body generators (rod, tube, shell and ball as octant, quarter,
!> half and whole sphere, box minus ball octant), each at two resolutions:
!> positive volumes and scaled Jacobians, volume and set areas converging to
!> the exact values at second order (flat faces on a curved surface: error
!> ~ h^2), nodes exactly on their circle or sphere (1e-12 relative) and
!> exactly on the symmetry planes, outward set faces, no coincident nodes,
!> every interior face shared by two hexes with opposite orientation and the
!> boundary exactly the union of the sets; spec validation messages.
program test_mesh_curved
  use core_kinds, only: rk, i8
  use core_sort, only: sort_order
  use core_status, only: status_t
  use mesh_geometry, only: hex_volume, quad_vector_area, HEX_FACE_NODES
  use mesh_global, only: global_mesh_t
  use mesh_curved, only: rod_spec_t, tube_spec_t, shell_spec_t, ball_spec_t, &
      box_minus_ball_spec_t, mesh_make_rod, mesh_make_tube, mesh_make_shell, &
      mesh_make_ball, mesh_make_box_minus_ball
  use check, only: check_true, check_close, check_summary
  implicit none
  real(rk), parameter :: PI = acos(-1.0_rk)
  !> Observed order of the volume and area errors between h and h/2: 2 less
  !> the higher-order terms of the chord error (about 0.01 at these sizes).
  real(rk), parameter :: MIN_ORDER = 1.9_rk
  !> Radius of nodes on a circle or sphere, relative.
  real(rk), parameter :: RADIUS_TOL = 1.0e-12_rk
  !> Distinct nodes are at least this fraction of the body size apart.
  real(rk), parameter :: COINCIDE_TOL = 1.0e-9_rk
  !> Flat sets (planes bounded by straight edges) are exact to round-off.
  real(rk), parameter :: FLAT_TOL = 1.0e3_rk * epsilon(1.0_rk)
  !> Required minimum scaled Jacobian at the default resolutions.
  real(rk), parameter :: MIN_JACOBIAN = 0.2_rk

  call test_rod('quarter')
  call test_rod('full')
  call test_tube('full')
  call test_tube('half')
  call test_tube('quarter')
  call test_tube_placed()
  call test_shell()
  call test_ball()
  call test_box_minus_ball()
  call test_sectors('quarter', 0.25_rk, [1, 2])
  call test_sectors('half', 0.5_rk, [2])
  call test_sectors('full', 1.0_rk, [integer ::])
  call test_defaults()
  call test_bad_specs()
  call check_summary()

contains

  subroutine test_rod(sector)
    character(len=*), intent(in) :: sector
    type(rod_spec_t) :: spec
    type(global_mesh_t) :: mesh
    type(status_t) :: status
    real(rk) :: volume(2), side(2), bottom(2), top(2), exact_side, exact_end, fraction, r
    integer :: level, nc, nr, nz, per_layer
    character(len=:), allocatable :: label

    fraction = 0.25_rk
    if (sector == 'full') fraction = 1.0_rk
    r = 1.3_rk
    do level = 1, 2
      spec = rod_spec_t(radius=r, length=2.5_rk, z0=-0.5_rk, sector=sector, &
          n_core=3 * level, n_radial=2 * level, n_axial=2 * level, axial_ratio=1.5_rk)
      call mesh_make_rod(spec, mesh, status)
      label = 'rod ' // sector // ' level ' // digit(level)
      call check_true(label // ': made', status%ok())
      nc = spec%n_core
      nr = spec%n_radial
      nz = spec%n_axial
      if (sector == 'full') then
        per_layer = (2 * nc + 1)**2 + 8 * nc * nr
        call check_true(label // ': zones', mesh%nzone == nz * 4 * (nc * nc + 2 * nc * nr))
      else
        per_layer = (nc + 1)**2 + 2 * nr * (nc + 1) - nr
        call check_true(label // ': zones', mesh%nzone == nz * (nc * nc + 2 * nc * nr))
      end if
      call check_true(label // ': nodes', mesh%nnode == per_layer * (nz + 1))
      volume(level) = check_mesh(label, mesh, max(spec%radius, spec%length))
      side(level) = set_area(mesh, 'side')
      bottom(level) = set_area(mesh, 'bottom')
      top(level) = set_area(mesh, 'top')
      call check_on_cylinder(label // ': side', mesh, 'side', [0.0_rk, 0.0_rk, 0.0_rk], &
          [0.0_rk, 0.0_rk, 1.0_rk], spec%radius)
      call check_radial_outward(label // ': side', mesh, 'side', [0.0_rk, 0.0_rk, 0.0_rk], &
          [0.0_rk, 0.0_rk, 1.0_rk], 1.0_rk)
      call check_plane(label // ': bottom', mesh, 'bottom', 3, spec%z0, &
          [0.0_rk, 0.0_rk, -1.0_rk])
      call check_plane(label // ': top', mesh, 'top', 3, spec%z0 + spec%length, &
          [0.0_rk, 0.0_rk, 1.0_rk])
      if (sector == 'quarter') then
        call check_plane(label // ': xsym', mesh, 'xsym', 1, 0.0_rk, [-1.0_rk, 0.0_rk, 0.0_rk])
        call check_plane(label // ': ysym', mesh, 'ysym', 2, 0.0_rk, [0.0_rk, -1.0_rk, 0.0_rk])
        call check_close(label // ': xsym area', set_area(mesh, 'xsym'), r * spec%length, &
            FLAT_TOL)
        call check_close(label // ': ysym area', set_area(mesh, 'ysym'), r * spec%length, &
            FLAT_TOL)
        call check_true(label // ': set names', mesh%nset == 5)
      else
        call check_true(label // ': set names', mesh%nset == 3)
      end if
    end do
    label = 'rod ' // sector
    exact_side = fraction * 2.0_rk * PI * r * spec%length
    exact_end = fraction * PI * r**2
    call check_order(label // ' volume', volume, fraction * PI * r**2 * spec%length)
    call check_order(label // ' side area', side, exact_side)
    call check_order(label // ' bottom area', bottom, exact_end)
    call check_order(label // ' top area', top, exact_end)
    call mesh%free()
  end subroutine test_rod

  subroutine test_tube(sector)
    character(len=*), intent(in) :: sector
    type(tube_spec_t) :: spec
    type(global_mesh_t) :: mesh
    type(status_t) :: status
    real(rk) :: volume(2), inner(2), outer(2), bottom(2), span, ri, ro, zaxis(3), zero(3)
    integer :: level, base, nodes_around
    character(len=:), allocatable :: label

    select case (sector)
    case ('full')
      span = 2.0_rk * PI
      base = 8
    case ('half')
      span = PI
      base = 4
    case default
      span = 0.5_rk * PI
      base = 2
    end select
    ri = 0.8_rk
    ro = 1.0_rk
    zaxis = [0.0_rk, 0.0_rk, 1.0_rk]
    zero = 0.0_rk
    do level = 1, 2
      spec = tube_spec_t(ri=ri, ro=ro, length=2.0_rk, sector=sector, n_theta=base * level, &
          n_radial=2 * level, n_axial=2 * level)
      call mesh_make_tube(spec, mesh, status)
      label = 'tube ' // sector // ' level ' // digit(level)
      call check_true(label // ': made', status%ok())
      nodes_around = spec%n_theta + 1
      if (sector == 'full') nodes_around = spec%n_theta
      call check_true(label // ': nodes', mesh%nnode == nodes_around * (spec%n_radial + 1) &
          * (spec%n_axial + 1))
      volume(level) = check_mesh(label, mesh, spec%length)
      inner(level) = set_area(mesh, 'inner')
      outer(level) = set_area(mesh, 'outer')
      bottom(level) = set_area(mesh, 'bottom')
      call check_close(label // ': top area = bottom area', set_area(mesh, 'top'), &
          bottom(level), FLAT_TOL)
      call check_on_cylinder(label // ': inner', mesh, 'inner', zero, zaxis, ri)
      call check_on_cylinder(label // ': outer', mesh, 'outer', zero, zaxis, ro)
      call check_radial_outward(label // ': inner', mesh, 'inner', zero, zaxis, -1.0_rk)
      call check_radial_outward(label // ': outer', mesh, 'outer', zero, zaxis, 1.0_rk)
      call check_plane(label // ': bottom', mesh, 'bottom', 3, 0.0_rk, -zaxis)
      call check_plane(label // ': top', mesh, 'top', 3, spec%length, zaxis)
      select case (sector)
      case ('half')
        call check_plane(label // ': ysym', mesh, 'ysym', 2, 0.0_rk, [0.0_rk, -1.0_rk, 0.0_rk])
        call check_close(label // ': ysym area', set_area(mesh, 'ysym'), &
            2.0_rk * (ro - ri) * spec%length, FLAT_TOL)
        call check_true(label // ': sets', mesh%nset == 5)
      case ('quarter')
        call check_plane(label // ': xsym', mesh, 'xsym', 1, 0.0_rk, [-1.0_rk, 0.0_rk, 0.0_rk])
        call check_plane(label // ': ysym', mesh, 'ysym', 2, 0.0_rk, [0.0_rk, -1.0_rk, 0.0_rk])
        call check_close(label // ': xsym area', set_area(mesh, 'xsym'), &
            (ro - ri) * spec%length, FLAT_TOL)
        call check_close(label // ': ysym area', set_area(mesh, 'ysym'), &
            (ro - ri) * spec%length, FLAT_TOL)
        call check_true(label // ': sets', mesh%nset == 6)
      case default
        call check_true(label // ': sets', mesh%nset == 4)
      end select
    end do
    label = 'tube ' // sector
    call check_order(label // ' volume', volume, 0.5_rk * span * (ro**2 - ri**2) * spec%length)
    call check_order(label // ' inner area', inner, span * ri * spec%length)
    call check_order(label // ' outer area', outer, span * ro * spec%length)
    call check_order(label // ' bottom area', bottom, 0.5_rk * span * (ro**2 - ri**2))
    call mesh%free()
  end subroutine test_tube

  !> A tube on a slanted axis, and a crossed pair as in problems D4/D5.
  subroutine test_tube_placed()
    type(tube_spec_t) :: spec, other
    type(global_mesh_t) :: mesh, mesh2
    type(status_t) :: status
    real(rk) :: axis(3), origin(3), volume, gap, distance
    integer :: i, j
    character(len=*), parameter :: label = 'tube placed'

    axis = [0.0_rk, 0.6_rk, 0.8_rk]
    origin = [1.0_rk, -2.0_rk, 3.0_rk]
    spec = tube_spec_t(ri=0.8_rk, ro=1.0_rk, length=3.0_rk, n_theta=24, n_radial=2, &
        n_axial=6, axis=axis, origin=origin)
    call mesh_make_tube(spec, mesh, status)
    call check_true(label // ': made', status%ok())
    volume = check_mesh(label, mesh, 4.0_rk)
    call check_close(label // ': volume = polygonal annulus', volume, 0.5_rk * 24 * &
        sin(2.0_rk * PI / 24) * (1.0_rk - 0.64_rk) * 3.0_rk, 1.0e-12_rk)
    call check_on_cylinder(label // ': inner', mesh, 'inner', origin, axis, 0.8_rk)
    call check_on_cylinder(label // ': outer', mesh, 'outer', origin, axis, 1.0_rk)
    call check_radial_outward(label // ': inner', mesh, 'inner', origin, axis, -1.0_rk)
    call check_radial_outward(label // ': outer', mesh, 'outer', origin, axis, 1.0_rk)
    call check_outward(label // ': bottom', mesh, 'bottom', -axis)
    call check_outward(label // ': top', mesh, 'top', axis)
    call check_true(label // ': bottom nodes in the plane through origin', &
        max_plane_distance(mesh, 'bottom', origin, axis) < 1.0e-14_rk * 4)
    call check_true(label // ': top nodes in the plane through the end', &
        max_plane_distance(mesh, 'top', origin + 3.0_rk * axis, axis) < 1.0e-14_rk * 8)

    ! Crossed tubes: one along x centred on the origin, one along y above it
    ! with a gap of 0.05 between the outer surfaces.
    gap = 0.05_rk
    spec = tube_spec_t(ri=0.8_rk, ro=1.0_rk, length=8.0_rk, n_theta=32, n_radial=2, &
        n_axial=16, axis=[1.0_rk, 0.0_rk, 0.0_rk], origin=[-4.0_rk, 0.0_rk, 0.0_rk])
    other = spec
    other%axis = [0.0_rk, 1.0_rk, 0.0_rk]
    other%origin = [0.0_rk, -4.0_rk, 2.0_rk + gap]
    call mesh_make_tube(spec, mesh, status)
    call mesh_make_tube(other, mesh2, status)
    call check_true('crossed tubes: made', status%ok())
    volume = check_mesh('crossed tube x', mesh, 8.0_rk)
    volume = check_mesh('crossed tube y', mesh2, 8.0_rk)
    distance = huge(1.0_rk)
    do j = 1, mesh2%nnode
      do i = 1, mesh%nnode
        distance = min(distance, norm2(mesh%coordinates(:, i) - mesh2%coordinates(:, j)))
      end do
    end do
    call check_close('crossed tubes: closest nodes are the gap apart', distance, gap, &
        1.0e-12_rk)
    call check_on_cylinder('crossed tube y: outer', mesh2, 'outer', other%origin, other%axis, &
        1.0_rk)
    call mesh%free()
    call mesh2%free()
  end subroutine test_tube_placed

  subroutine test_shell()
    type(shell_spec_t) :: spec
    type(global_mesh_t) :: mesh
    type(status_t) :: status
    real(rk) :: volume(2), inner(2), outer(2), sym(2, 3), ri, ro, zero(3)
    integer :: level, np, axis
    character(len=*), parameter :: names(3) = ['xsym', 'ysym', 'zsym']
    character(len=:), allocatable :: label

    ri = 0.8_rk
    ro = 1.0_rk
    zero = 0.0_rk
    do level = 1, 2
      spec = shell_spec_t(ri=ri, ro=ro, n_patch=4 * level, n_radial=2 * level)
      call mesh_make_shell(spec, mesh, status)
      label = 'shell level ' // digit(level)
      call check_true(label // ': made', status%ok())
      np = spec%n_patch
      call check_true(label // ': nodes', mesh%nnode == (3 * (np + 1)**2 - 3 * (np + 1) + 1) &
          * (spec%n_radial + 1))
      call check_true(label // ': zones', mesh%nzone == 3 * np * np * spec%n_radial)
      volume(level) = check_mesh(label, mesh, ro)
      inner(level) = set_area(mesh, 'inner')
      outer(level) = set_area(mesh, 'outer')
      call check_on_sphere(label // ': inner', mesh, 'inner', ri)
      call check_on_sphere(label // ': outer', mesh, 'outer', ro)
      call check_radial_outward(label // ': inner', mesh, 'inner', zero, zero, -1.0_rk)
      call check_radial_outward(label // ': outer', mesh, 'outer', zero, zero, 1.0_rk)
      do axis = 1, 3
        call check_plane(label // ': ' // names(axis), mesh, names(axis), axis, 0.0_rk, &
            -unit(axis))
        sym(level, axis) = set_area(mesh, names(axis))
      end do
    end do
    call check_order('shell volume', volume, PI / 6.0_rk * (ro**3 - ri**3))
    call check_order('shell inner area', inner, 0.5_rk * PI * ri**2)
    call check_order('shell outer area', outer, 0.5_rk * PI * ro**2)
    do axis = 1, 3
      call check_order('shell ' // names(axis) // ' area', sym(:, axis), &
          0.25_rk * PI * (ro**2 - ri**2))
    end do
    call mesh%free()
  end subroutine test_shell

  !> Ball octant: volume pi R^3 / 6, sphere area pi R^2 / 2, quarter discs.
  subroutine test_ball()
    type(ball_spec_t) :: spec
    type(global_mesh_t) :: mesh
    type(status_t) :: status
    real(rk) :: volume(2), outer(2), sym(2, 3), r, zero(3)
    integer :: level, nc, nr, axis
    character(len=*), parameter :: names(3) = ['xmin', 'ymin', 'zmin']
    character(len=:), allocatable :: label

    r = 0.7_rk
    zero = 0.0_rk
    do level = 1, 2
      spec = ball_spec_t(radius=r, n_core=4 * level, n_radial=3 * level, radial_ratio=0.8_rk)
      call mesh_make_ball(spec, mesh, status)
      label = 'ball level ' // digit(level)
      call check_true(label // ': made', status%ok())
      nc = spec%n_core
      nr = spec%n_radial
      call check_true(label // ': zones', mesh%nzone == nc**3 + 3 * nc * nc * nr)
      call check_true(label // ': nodes', mesh%nnode == (nc + 1)**3 + (3 * (nc + 1)**2 &
          - 3 * (nc + 1) + 1) * nr)
      call check_true(label // ': sets', mesh%nset == 4)
      volume(level) = check_mesh(label, mesh, r, quality=.true.)
      outer(level) = set_area(mesh, 'outer')
      call check_on_sphere(label // ': outer', mesh, 'outer', r)
      call check_radial_outward(label // ': outer', mesh, 'outer', zero, zero, 1.0_rk)
      do axis = 1, 3
        call check_plane(label // ': ' // names(axis), mesh, names(axis), axis, 0.0_rk, &
            -unit(axis))
        sym(level, axis) = set_area(mesh, names(axis))
      end do
    end do
    call check_order('ball volume', volume, PI / 6.0_rk * r**3)
    call check_order('ball outer area', outer, 0.5_rk * PI * r**2)
    do axis = 1, 3
      call check_order('ball ' // names(axis) // ' area', sym(:, axis), 0.25_rk * PI * r**2)
    end do
    call mesh%free()
  end subroutine test_ball

  !> Ball and shell sectors beyond the octant ('quarter': x, y >= 0; 'half':
  !> y >= 0; 'full'): copies of the octant merged across the planes they
  !> share. Volume and sphere area converge at second order to the sector's
  !> share of the exact values (1/4, 1/2, 1); the planes the sector ends on
  !> are flat sets of the exact half or whole disc (annulus), facing out;
  !> the planes inside are gone (check_mesh: no coincident nodes, every
  !> interior face shared by two hexes, the boundary exactly the sets).
  subroutine test_sectors(sector, share, planes)
    character(len=*), intent(in) :: sector
    real(rk), intent(in) :: share !< of the whole sphere
    integer, intent(in) :: planes(:) !< axes of the planes the sector ends on
    type(ball_spec_t) :: ball
    type(shell_spec_t) :: shell
    type(global_mesh_t) :: mesh
    type(status_t) :: status
    real(rk) :: volume(2, 2), outer(2, 2), plane_area(2, 2, 3), r, ri, ro, zero(3)
    integer :: level, a, copies
    character(len=*), parameter :: ball_names(3) = ['xmin', 'ymin', 'zmin']
    character(len=*), parameter :: shell_names(3) = ['xsym', 'ysym', 'zsym']
    character(len=:), allocatable :: label

    r = 0.7_rk
    ri = 0.8_rk
    ro = 1.0_rk
    zero = 0.0_rk
    copies = nint(8.0_rk * share)
    plane_area = 0.0_rk
    do level = 1, 2
      ball = ball_spec_t(radius=r, n_core=4 * level, n_radial=3 * level, radial_ratio=0.8_rk, &
          sector=sector)
      call mesh_make_ball(ball, mesh, status)
      label = 'ball ' // sector // ' level ' // digit(level)
      call check_true(label // ': made', status%ok())
      call check_true(label // ': zones', mesh%nzone == copies * (ball%n_core**3 + 3 * &
          ball%n_core**2 * ball%n_radial))
      call check_true(label // ': sets', mesh%nset == 1 + size(planes))
      volume(1, level) = check_mesh(label, mesh, r, quality=.true.)
      outer(1, level) = set_area(mesh, 'outer')
      call check_on_sphere(label // ': outer', mesh, 'outer', r)
      call check_radial_outward(label // ': outer', mesh, 'outer', zero, zero, 1.0_rk)
      do a = 1, size(planes)
        call check_plane(label // ': ' // ball_names(planes(a)), mesh, ball_names(planes(a)), &
            planes(a), 0.0_rk, -unit(planes(a)))
        plane_area(1, level, a) = set_area(mesh, ball_names(planes(a)))
      end do
      shell = shell_spec_t(ri=ri, ro=ro, n_patch=4 * level, n_radial=2 * level, sector=sector)
      call mesh_make_shell(shell, mesh, status)
      label = 'shell ' // sector // ' level ' // digit(level)
      call check_true(label // ': made', status%ok())
      call check_true(label // ': zones', mesh%nzone == copies * 3 * shell%n_patch**2 * &
          shell%n_radial)
      call check_true(label // ': sets', mesh%nset == 2 + size(planes))
      volume(2, level) = check_mesh(label, mesh, ro)
      outer(2, level) = set_area(mesh, 'outer')
      call check_on_sphere(label // ': inner', mesh, 'inner', ri)
      call check_on_sphere(label // ': outer', mesh, 'outer', ro)
      call check_radial_outward(label // ': inner', mesh, 'inner', zero, zero, -1.0_rk)
      do a = 1, size(planes)
        call check_plane(label // ': ' // shell_names(planes(a)), mesh, &
            shell_names(planes(a)), planes(a), 0.0_rk, -unit(planes(a)))
        plane_area(2, level, a) = set_area(mesh, shell_names(planes(a)))
      end do
    end do
    call check_order('ball ' // sector // ' volume', volume(1, :), share * 4.0_rk / 3.0_rk &
        * PI * r**3)
    call check_order('ball ' // sector // ' outer area', outer(1, :), share * 4.0_rk * PI &
        * r**2)
    call check_order('shell ' // sector // ' volume', volume(2, :), share * 4.0_rk / 3.0_rk &
        * PI * (ro**3 - ri**3))
    call check_order('shell ' // sector // ' outer area', outer(2, :), share * 4.0_rk * PI &
        * ro**2)
    ! A plane the sector ends on holds 2 share of the disc (a quarter
    ! sphere ends on two half discs, a half sphere on one whole disc).
    do a = 1, size(planes)
      call check_order('ball ' // sector // ' plane area', plane_area(1, :, a), 2.0_rk * &
          share * PI * r**2)
      call check_order('shell ' // sector // ' plane area', plane_area(2, :, a), 2.0_rk * &
          share * PI * (ro**2 - ri**2))
    end do
    call mesh%free()
  end subroutine test_sectors

  !> Box minus ball octant: volume L^3 - pi R^3 / 6, sphere area pi R^2 / 2,
  !> outer faces L^2 exactly, symmetry faces L^2 - pi R^2 / 4.
  subroutine test_box_minus_ball()
    type(box_minus_ball_spec_t) :: spec
    type(global_mesh_t) :: mesh
    type(status_t) :: status
    real(rk) :: volume(2), inner(2), sym(2, 3), r, length, zero(3)
    integer :: level, np, axis
    character(len=*), parameter :: lower(3) = ['xmin', 'ymin', 'zmin']
    character(len=*), parameter :: upper(3) = ['xmax', 'ymax', 'zmax']
    character(len=:), allocatable :: label

    r = 0.5_rk
    length = 1.2_rk
    zero = 0.0_rk
    do level = 1, 2
      spec = box_minus_ball_spec_t(radius=r, length=length, n_patch=4 * level, &
          n_radial=3 * level, radial_ratio=1.5_rk)
      call mesh_make_box_minus_ball(spec, mesh, status)
      label = 'box minus ball level ' // digit(level)
      call check_true(label // ': made', status%ok())
      np = spec%n_patch
      call check_true(label // ': zones', mesh%nzone == 3 * np * np * spec%n_radial)
      call check_true(label // ': nodes', mesh%nnode == (3 * (np + 1)**2 - 3 * (np + 1) + 1) &
          * (spec%n_radial + 1))
      call check_true(label // ': sets', mesh%nset == 7)
      volume(level) = check_mesh(label, mesh, length, quality=.true.)
      inner(level) = set_area(mesh, 'inner')
      call check_on_sphere(label // ': inner', mesh, 'inner', r)
      call check_radial_outward(label // ': inner', mesh, 'inner', zero, zero, -1.0_rk)
      do axis = 1, 3
        call check_plane(label // ': ' // lower(axis), mesh, lower(axis), axis, 0.0_rk, &
            -unit(axis))
        call check_plane(label // ': ' // upper(axis), mesh, upper(axis), axis, length, &
            unit(axis))
        call check_close(label // ': ' // upper(axis) // ' area', set_area(mesh, upper(axis)), &
            length**2, FLAT_TOL)
        sym(level, axis) = set_area(mesh, lower(axis))
      end do
    end do
    call check_order('box minus ball volume', volume, length**3 - PI / 6.0_rk * r**3)
    call check_order('box minus ball inner area', inner, 0.5_rk * PI * r**2)
    do axis = 1, 3
      call check_order('box minus ball ' // lower(axis) // ' area', sym(:, axis), &
          length**2 - 0.25_rk * PI * r**2)
    end do
    call mesh%free()
  end subroutine test_box_minus_ball

  !> Every generator at its default resolution: quality and volume.
  subroutine test_defaults()
    type(global_mesh_t) :: mesh
    type(status_t) :: status
    type(rod_spec_t) :: rod
    type(tube_spec_t) :: tube
    type(shell_spec_t) :: shell
    type(ball_spec_t) :: ball
    type(box_minus_ball_spec_t) :: box_minus_ball
    real(rk) :: volume

    call mesh_make_rod(rod, mesh, status)
    volume = check_mesh('default quarter rod', mesh, 4.0_rk, quality=.true.)
    call check_close('default quarter rod: volume', volume, 0.25_rk * PI * 4.0_rk, 5.0e-3_rk)
    rod%sector = 'full'
    call mesh_make_rod(rod, mesh, status)
    volume = check_mesh('default full rod', mesh, 4.0_rk, quality=.true.)
    call mesh_make_tube(tube, mesh, status)
    volume = check_mesh('default full tube', mesh, 8.0_rk, quality=.true.)
    call check_close('default tube: volume', volume, PI * 0.36_rk * 8.0_rk, 5.0e-3_rk)
    call mesh_make_shell(shell, mesh, status)
    volume = check_mesh('default shell', mesh, 10.0_rk, quality=.true.)
    call check_close('default shell: volume', volume, PI / 6.0_rk * 488.0_rk, 5.0e-3_rk)
    call mesh_make_ball(ball, mesh, status)
    volume = check_mesh('default ball', mesh, 0.5_rk, quality=.true.)
    call check_close('default ball: volume', volume, PI / 48.0_rk, 5.0e-3_rk)
    call mesh_make_box_minus_ball(box_minus_ball, mesh, status)
    volume = check_mesh('default box minus ball', mesh, 1.2_rk, quality=.true.)
    call check_close('default box minus ball: volume', volume, 1.728_rk - PI / 48.0_rk, &
        5.0e-3_rk)
    call check_true('defaults: made', status%ok())
    call mesh%free()
  end subroutine test_defaults

  subroutine test_bad_specs()
    type(global_mesh_t) :: mesh
    type(status_t) :: status
    type(tube_spec_t) :: tube

    call mesh_make_rod(rod_spec_t(radius=-1.0_rk, sector='half', n_axial=0), mesh, status)
    call check_true('bad rod: three problems', status%count == 3)
    call check_true('bad rod: radius named', index(status%messages(1), 'rod: radius') == 1)
    call check_true('bad rod: sector named', index(status%messages(2), 'rod: sector') == 1)
    call check_true('bad rod: n_axial named', index(status%messages(3), 'rod: n_axial') == 1)
    call check_true('bad rod: no mesh', mesh%nnode == 0 .and. .not. allocated(mesh%coordinates))
    call status%clear()
    call mesh_make_rod(rod_spec_t(core_fraction=0.8_rk), mesh, status)
    call check_true('bad rod: core_fraction named', status%count == 1 .and. &
        index(status%messages(1), 'rod: core_fraction') == 1)
    call status%clear()

    tube%ri = 1.0_rk
    tube%ro = 0.5_rk
    tube%n_theta = 2
    tube%axis = [0.0_rk, 0.0_rk, 2.0_rk]
    call mesh_make_tube(tube, mesh, status)
    call check_true('bad tube: three problems', status%count == 3)
    call check_true('bad tube: ro named', index(status%messages(1), 'tube: ro') == 1)
    call check_true('bad tube: n_theta named', index(status%messages(2), 'tube: n_theta') == 1)
    call check_true('bad tube: axis named', index(status%messages(3), 'tube: axis') == 1)
    call status%clear()
    call mesh_make_tube(tube_spec_t(ri=0.0_rk, radial_reference=[0.0_rk, 0.0_rk, 1.0_rk]), &
        mesh, status)
    call check_true('bad tube: ri and radial_reference', status%count == 2 .and. &
        index(status%messages(1), 'tube: ri') == 1 .and. &
        index(status%messages(2), 'tube: radial_reference') == 1)
    call status%clear()

    call mesh_make_shell(shell_spec_t(ri=10.0_rk, ro=8.0_rk, n_patch=0, &
        radial_ratio=0.0_rk), mesh, status)
    call check_true('bad shell: three problems', status%count == 3)
    call check_true('bad shell: ro named', index(status%messages(1), 'shell: ro') == 1)
    call check_true('bad shell: n_patch named', index(status%messages(2), 'shell: n_patch') == 1)
    call check_true('bad shell: radial_ratio named', &
        index(status%messages(3), 'shell: radial_ratio') == 1)
    call status%clear()

    call mesh_make_ball(ball_spec_t(radius=0.0_rk, n_radial=0, core_fraction=0.6_rk), &
        mesh, status)
    call check_true('bad ball: three problems', status%count == 3)
    call check_true('bad ball: radius named', index(status%messages(1), 'ball: radius') == 1)
    call check_true('bad ball: n_radial named', index(status%messages(2), 'ball: n_radial') == 1)
    call check_true('bad ball: core_fraction named', &
        index(status%messages(3), 'ball: core_fraction') == 1)
    call status%clear()

    call mesh_make_box_minus_ball(box_minus_ball_spec_t(radius=1.0_rk, length=0.8_rk, &
        n_patch=0, radial_ratio=-1.0_rk), mesh, status)
    call check_true('bad box minus ball: three problems', status%count == 3)
    call check_true('bad box minus ball: length named', &
        index(status%messages(1), 'box_minus_ball: length') == 1)
    call check_true('bad box minus ball: n_patch named', &
        index(status%messages(2), 'box_minus_ball: n_patch') == 1)
    call check_true('bad box minus ball: radial_ratio named', &
        index(status%messages(3), 'box_minus_ball: radial_ratio') == 1)
  end subroutine test_bad_specs

  ! ------------------------------------------------------------- whole mesh

  !> Volumes, quality, coincident nodes and face topology; returns the volume.
  real(rk) function check_mesh(label, mesh, length_scale, quality) result(total)
    character(len=*), intent(in) :: label
    type(global_mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: length_scale
    logical, intent(in), optional :: quality !< require min scaled Jacobian > MIN_JACOBIAN
    real(rk) :: x(3, 8), volume, vmin, jmin
    integer :: z
    character(len=120) :: text

    total = 0.0_rk
    vmin = huge(1.0_rk)
    jmin = huge(1.0_rk)
    do z = 1, mesh%nzone
      x = mesh%coordinates(:, mesh%connectivity(:, z))
      volume = hex_volume(x)
      total = total + volume
      vmin = min(vmin, volume)
      jmin = min(jmin, scaled_jacobian(x))
    end do
    write(text, '(a,i0,a,i0,a,f6.4)') ': ', mesh%nzone, ' zones, ', mesh%nnode, &
        ' nodes, min scaled Jacobian ', jmin
    call check_true(label // trim(text), mesh%nzone > 0 .and. jmin > 0.0_rk)
    call check_true(label // ': all volumes > 0', vmin > 0.0_rk)
    if (present(quality)) then
      if (quality) call check_true(label // ': min scaled Jacobian > 0.2', jmin > MIN_JACOBIAN)
    end if
    call check_true(label // ': zone_block all 0', all(mesh%zone_block == 0))
    call check_true(label // ': no coincident nodes', &
        count_coincident(mesh, COINCIDE_TOL * length_scale) == 0)
    call check_topology(label, mesh)
  end function check_mesh

  !> Minimum over the 8 corners of det[e1 e2 e3] / (|e1| |e2| |e3|).
  real(rk) function scaled_jacobian(x) result(jmin)
    real(rk), intent(in) :: x(3, 8)
    integer, parameter :: EDGES(3, 8) = reshape([2, 4, 5, 3, 1, 6, 4, 2, 7, 1, 3, 8, &
        8, 6, 1, 5, 7, 2, 6, 8, 3, 7, 5, 4], [3, 8])
    real(rk) :: e(3, 3)
    integer :: c, m
    jmin = huge(1.0_rk)
    do c = 1, 8
      do m = 1, 3
        e(:, m) = x(:, EDGES(m, c)) - x(:, c)
        e(:, m) = e(:, m) / norm2(e(:, m))
      end do
      jmin = min(jmin, dot_product(e(:, 1), cross(e(:, 2), e(:, 3))))
    end do
  end function scaled_jacobian

  !> Pairs of nodes closer than tolerance (sort along a direction, then scan).
  integer function count_coincident(mesh, tolerance) result(pairs)
    type(global_mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: tolerance
    real(rk), parameter :: DIRECTION(3) = [0.3_rk, 0.5_rk, 0.81_rk]
    real(rk), allocatable :: key(:)
    integer, allocatable :: order(:)
    integer :: a, c
    key = matmul(DIRECTION, mesh%coordinates)
    call sort_order(key, order)
    pairs = 0
    do a = 1, mesh%nnode
      do c = a + 1, mesh%nnode
        if (key(order(c)) - key(order(a)) > tolerance * norm2(DIRECTION)) exit
        if (norm2(mesh%coordinates(:, order(c)) - mesh%coordinates(:, order(a))) < tolerance) &
            pairs = pairs + 1
      end do
    end do
  end function count_coincident

  !> Faces by their sorted node ids: interior faces shared by exactly two hexes
  !> with opposite vector areas, boundary faces each in exactly one set, and
  !> every set face a boundary face.
  subroutine check_topology(label, mesh)
    character(len=*), intent(in) :: label
    type(global_mesh_t), intent(in) :: mesh
    integer, allocatable :: keys(:, :), order(:), multiplicity(:), covered(:)
    real(rk) :: area1(3), area2(3)
    integer :: nface, z, f, a, c, m, face, bad_share, bad_pair, bad_set, nboundary
    nface = 6 * mesh%nzone
    allocate(keys(4, nface), multiplicity(nface), covered(nface))
    do z = 1, mesh%nzone
      do f = 1, 6
        keys(:, 6 * (z - 1) + f) = sort4(int(mesh%connectivity(HEX_FACE_NODES(:, f), z)))
      end do
    end do
    call sort_order(int(keys, i8), order)
    bad_share = 0
    bad_pair = 0
    a = 1
    do while (a <= nface)
      c = a
      do while (c < nface)
        if (any(keys(:, order(c + 1)) /= keys(:, order(a)))) exit
        c = c + 1
      end do
      m = c - a + 1
      multiplicity(order(a:c)) = m
      if (m > 2) bad_share = bad_share + 1
      if (m == 2) then
        area1 = face_area(mesh, order(a))
        area2 = face_area(mesh, order(c))
        if (norm2(area1 + area2) > 1.0e-12_rk * norm2(area1)) bad_pair = bad_pair + 1
      end if
      a = c + 1
    end do
    covered = 0
    bad_set = 0
    do a = 1, mesh%set_start(mesh%nset + 1) - 1
      face = 6 * (int(mesh%set_zone(a)) - 1) + int(mesh%set_face(a))
      covered(face) = covered(face) + 1
      if (multiplicity(face) /= 1) bad_set = bad_set + 1
    end do
    nboundary = count(multiplicity == 1)
    call check_true(label // ': no face shared by more than two hexes', bad_share == 0)
    call check_true(label // ': shared faces have opposite orientation', bad_pair == 0)
    call check_true(label // ': every set face is on the boundary', bad_set == 0)
    call check_true(label // ': every boundary face in exactly one set', &
        all(covered(pack([(f, f = 1, nface)], multiplicity == 1)) == 1) .and. &
        sum(covered) == nboundary)
  end subroutine check_topology

  ! ------------------------------------------------------------- face sets

  !> Sum of the magnitudes of the vector areas of a set's faces.
  real(rk) function set_area(mesh, name) result(area)
    type(global_mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: name
    integer :: s, a
    area = 0.0_rk
    s = mesh%find_set(name)
    if (s == 0) then
      call check_true('set ' // name // ' exists', .false.)
      return
    end if
    do a = mesh%set_start(s), mesh%set_start(s + 1) - 1
      area = area + norm2(face_area(mesh, set_index(mesh, a)))
    end do
  end function set_area

  !> Nodes at distance radius from the line origin + t axis; faces outward.
  subroutine check_on_cylinder(label, mesh, name, origin, axis, radius)
    character(len=*), intent(in) :: label, name
    type(global_mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: origin(3), axis(3), radius
    real(rk) :: worst, d(3)
    integer :: s, a, k, node
    worst = 0.0_rk
    s = mesh%find_set(name)
    do a = mesh%set_start(s), mesh%set_start(s + 1) - 1
      do k = 1, 4
        node = face_node(mesh, a, k)
        d = mesh%coordinates(:, node) - origin
        d = d - dot_product(d, axis) * axis
        worst = max(worst, abs(norm2(d) - radius) / radius)
      end do
    end do
    call check_true(label // ' nodes on the circle', worst <= RADIUS_TOL)
  end subroutine check_on_cylinder

  subroutine check_on_sphere(label, mesh, name, radius)
    character(len=*), intent(in) :: label, name
    type(global_mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: radius
    real(rk) :: worst
    integer :: s, a, k
    worst = 0.0_rk
    s = mesh%find_set(name)
    do a = mesh%set_start(s), mesh%set_start(s + 1) - 1
      do k = 1, 4
        worst = max(worst, abs(norm2(mesh%coordinates(:, face_node(mesh, a, k))) - radius) &
            / radius)
      end do
    end do
    call check_true(label // ' nodes on the sphere', worst <= RADIUS_TOL)
  end subroutine check_on_sphere

  !> Face normals along sign times the direction from the axis (or from the
  !> origin when axis is zero) to the face centre.
  subroutine check_radial_outward(label, mesh, name, origin, axis, sign)
    character(len=*), intent(in) :: label, name
    type(global_mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: origin(3), axis(3), sign
    real(rk) :: centre(3), worst
    integer :: s, a, k
    worst = huge(1.0_rk)
    s = mesh%find_set(name)
    do a = mesh%set_start(s), mesh%set_start(s + 1) - 1
      centre = 0.0_rk
      do k = 1, 4
        centre = centre + 0.25_rk * mesh%coordinates(:, face_node(mesh, a, k))
      end do
      centre = centre - origin
      centre = centre - dot_product(centre, axis) * axis
      worst = min(worst, sign * dot_product(face_area(mesh, set_index(mesh, a)), &
          centre / norm2(centre)) / norm2(face_area(mesh, set_index(mesh, a))))
    end do
    call check_true(label // ' faces point outward', worst > 0.5_rk)
  end subroutine check_radial_outward

  !> Every set node has coordinate component exactly equal to value, every
  !> face normal is along outward.
  subroutine check_plane(label, mesh, name, component, value, outward)
    character(len=*), intent(in) :: label, name
    type(global_mesh_t), intent(in) :: mesh
    integer, intent(in) :: component
    real(rk), intent(in) :: value, outward(3)
    logical :: exact
    integer :: s, a, k
    exact = .true.
    s = mesh%find_set(name)
    do a = mesh%set_start(s), mesh%set_start(s + 1) - 1
      do k = 1, 4
        exact = exact .and. mesh%coordinates(component, face_node(mesh, a, k)) == value
      end do
    end do
    call check_true(label // ' nodes exactly on the plane', exact)
    call check_outward(label, mesh, name, outward)
  end subroutine check_plane

  subroutine check_outward(label, mesh, name, outward)
    character(len=*), intent(in) :: label, name
    type(global_mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: outward(3)
    real(rk) :: worst, area(3)
    integer :: s, a
    worst = huge(1.0_rk)
    s = mesh%find_set(name)
    do a = mesh%set_start(s), mesh%set_start(s + 1) - 1
      area = face_area(mesh, set_index(mesh, a))
      worst = min(worst, dot_product(area, outward) / norm2(area))
    end do
    call check_true(label // ' faces point outward', worst > 1.0_rk - 1.0e-12_rk)
  end subroutine check_outward

  real(rk) function max_plane_distance(mesh, name, point, normal) result(worst)
    type(global_mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: name
    real(rk), intent(in) :: point(3), normal(3)
    integer :: s, a, k
    worst = 0.0_rk
    s = mesh%find_set(name)
    do a = mesh%set_start(s), mesh%set_start(s + 1) - 1
      do k = 1, 4
        worst = max(worst, abs(dot_product(mesh%coordinates(:, face_node(mesh, a, k)) - point, &
            normal)))
      end do
    end do
  end function max_plane_distance

  !> Errors at h and h/2 against exact: observed order >= MIN_ORDER.
  subroutine check_order(label, values, exact)
    character(len=*), intent(in) :: label
    real(rk), intent(in) :: values(2), exact
    real(rk) :: error(2), order
    character(len=120) :: text
    error = abs(values - exact) / abs(exact)
    order = log(error(1) / error(2)) / log(2.0_rk)
    write(text, '(a,es9.2,a,es9.2,a,f5.2)') ': relative error ', error(1), ' -> ', error(2), &
        ', order ', order
    call check_true(label // trim(text), order >= MIN_ORDER .and. error(2) < 0.05_rk)
  end subroutine check_order

  ! ------------------------------------------------------------- utilities

  !> Global face index 6 (zone - 1) + face of set entry a.
  integer function set_index(mesh, a)
    type(global_mesh_t), intent(in) :: mesh
    integer, intent(in) :: a
    set_index = 6 * (int(mesh%set_zone(a)) - 1) + int(mesh%set_face(a))
  end function set_index

  !> Node k (1..4) of the face of set entry a.
  integer function face_node(mesh, a, k)
    type(global_mesh_t), intent(in) :: mesh
    integer, intent(in) :: a, k
    face_node = int(mesh%connectivity(HEX_FACE_NODES(k, mesh%set_face(a)), mesh%set_zone(a)))
  end function face_node

  !> Vector area of global face index 6 (zone - 1) + face.
  function face_area(mesh, face) result(area)
    type(global_mesh_t), intent(in) :: mesh
    integer, intent(in) :: face
    real(rk) :: area(3)
    integer :: z, f
    z = (face - 1) / 6 + 1
    f = face - 6 * (z - 1)
    area = quad_vector_area(mesh%coordinates(:, mesh%connectivity(HEX_FACE_NODES(:, f), z)))
  end function face_area

  pure function sort4(v) result(s)
    integer, intent(in) :: v(4)
    integer :: s(4), i, j, t
    s = v
    do i = 2, 4
      t = s(i)
      j = i - 1
      do while (j >= 1)
        if (s(j) <= t) exit
        s(j + 1) = s(j)
        j = j - 1
      end do
      s(j + 1) = t
    end do
  end function sort4

  pure function cross(a, b) result(c)
    real(rk), intent(in) :: a(3), b(3)
    real(rk) :: c(3)
    c = [a(2) * b(3) - a(3) * b(2), a(3) * b(1) - a(1) * b(3), a(1) * b(2) - a(2) * b(1)]
  end function cross

  pure function unit(axis) result(e)
    integer, intent(in) :: axis
    real(rk) :: e(3)
    e = 0.0_rk
    e(axis) = 1.0_rk
  end function unit

  function digit(i) result(text)
    integer, intent(in) :: i
    character(len=:), allocatable :: text
    character(len=12) :: buffer
    write(buffer, '(i0)') i
    text = trim(buffer)
  end function digit

end program test_mesh_curved
