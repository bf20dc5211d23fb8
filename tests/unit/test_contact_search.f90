!> Contact search: the bucket search against an O(N^2) brute-force reference
!> (same territories, exclusions coded independently, same local search) on
!> thousands of random rigid placements of two bodies (box/box, box/quarter
!> rod, tube/box, shell octant/box) and on self-contact of a box bent into a
!> U; test pairs and primary pairs must agree exactly. Also the local search
!> on planar segments against the analytic projection, the gap sign, and the
!> invariance of the pairs under a relabelling of the segments.
program test_contact_search
  use, intrinsic :: iso_fortran_env, only: output_unit
  use core_kinds, only: rk, ik, i8
  use core_status, only: status_t
  use mesh_global, only: global_mesh_t, box_spec_t, mesh_make_box, NAME_LEN
  use mesh_curved, only: rod_spec_t, tube_spec_t, shell_spec_t, mesh_make_rod, &
      mesh_make_tube, mesh_make_shell
  use contact_surface, only: contact_surface_t, surface_build, surface_from_segments, &
      surface_update_edges
  use contact_search, only: primary_pair_t, bucket_search, closest_point, contact_kind, &
      primary_pairs, KIND_NONE, KIND_SEGMENT, LOCATION_FACE, &
      LOCATION_EDGE, LOCATION_CORNER
  use check, only: check_true, check_close, check_summary
  implicit none
  real(rk), parameter :: pi = 3.14159265358979323846264338327950288_rk
  !> Random placements per body pair, and self-contact folds.
  integer, parameter :: CASES_PER_PAIR = 500
  integer, parameter :: SELF_CASES = 500
  integer :: total_cases = 0
  integer :: count_kind(0:3) = 0
  integer(i8) :: total_pairs = 0

  call set_seed()
  call test_planar_projection()
  call test_gap_sign_on_box()
  call test_body_pairs()
  call test_self_contact()
  write(output_unit, '(a,i0,a,i0,a,3(i0,1x))') 'random cases: ', total_cases, &
      ', test pairs: ', total_pairs, ', primary segment/edge/node: ', count_kind(1:3)
  call check_summary()

contains

  subroutine set_seed()
    integer :: seed_size
    integer, allocatable :: seed(:)
    call random_seed(size=seed_size)
    allocate(seed(seed_size))
    seed = 20240611
    call random_seed(put=seed)
  end subroutine set_seed

  real(rk) function uniform(low, high)
    real(rk), intent(in) :: low, high
    real(rk) :: u
    call random_number(u)
    uniform = low + (high - low) * u
  end function uniform

  integer function random_int(n)
    integer, intent(in) :: n
    random_int = min(n, 1 + int(uniform(0.0_rk, real(n, rk))))
  end function random_int

  !> A uniformly random rotation (Shoemake), or a random proper signed
  !> permutation (exact right angles) when axis_aligned.
  function random_rotation(axis_aligned) result(r)
    logical, intent(in) :: axis_aligned
    real(rk) :: r(3, 3), u1, u2, u3, w, a, b, c
    integer :: order(3), i
    if (axis_aligned) then
      order = [1, 2, 3]
      do i = 3, 2, -1
        call swap(order(i), order(random_int(i)))
      end do
      r = 0.0_rk
      do i = 1, 3
        r(i, order(i)) = merge(1.0_rk, -1.0_rk, uniform(0.0_rk, 1.0_rk) < 0.5_rk)
      end do
      if (det3(r) < 0.0_rk) r(:, 1) = -r(:, 1)
      return
    end if
    u1 = uniform(0.0_rk, 1.0_rk)
    u2 = uniform(0.0_rk, 1.0_rk)
    u3 = uniform(0.0_rk, 1.0_rk)
    w = sqrt(1.0_rk - u1) * sin(2 * pi * u2)
    a = sqrt(1.0_rk - u1) * cos(2 * pi * u2)
    b = sqrt(u1) * sin(2 * pi * u3)
    c = sqrt(u1) * cos(2 * pi * u3)
    r(1, :) = [1 - 2 * (b * b + c * c), 2 * (a * b - w * c), 2 * (a * c + w * b)]
    r(2, :) = [2 * (a * b + w * c), 1 - 2 * (a * a + c * c), 2 * (b * c - w * a)]
    r(3, :) = [2 * (a * c - w * b), 2 * (b * c + w * a), 1 - 2 * (a * a + b * b)]
  end function random_rotation

  function cross3(u, v) result(w)
    real(rk), intent(in) :: u(3), v(3)
    real(rk) :: w(3)
    w = [u(2) * v(3) - u(3) * v(2), u(3) * v(1) - u(1) * v(3), u(1) * v(2) - u(2) * v(1)]
  end function cross3

  subroutine swap(i, j)
    integer, intent(inout) :: i, j
    integer :: t
    t = i
    i = j
    j = t
  end subroutine swap

  real(rk) function det3(r)
    real(rk), intent(in) :: r(3, 3)
    det3 = r(1, 1) * (r(2, 2) * r(3, 3) - r(2, 3) * r(3, 2)) &
        - r(1, 2) * (r(2, 1) * r(3, 3) - r(2, 3) * r(3, 1)) &
        + r(1, 3) * (r(2, 1) * r(3, 2) - r(2, 2) * r(3, 1))
  end function det3

  !> One mesh holding a and b; the sets are renamed 'a_<name>' and 'b_<name>'.
  subroutine merge_meshes(a, b, mesh)
    type(global_mesh_t), intent(in) :: a, b
    type(global_mesh_t), intent(inout) :: mesh
    integer :: s
    call mesh%free()
    mesh%nnode = a%nnode + b%nnode
    mesh%nzone = a%nzone + b%nzone
    mesh%coordinates = reshape([a%coordinates, b%coordinates], [3, mesh%nnode])
    mesh%connectivity = reshape([a%connectivity, b%connectivity + a%nnode], [8, mesh%nzone])
    mesh%nset = a%nset + b%nset
    allocate(mesh%set_name(mesh%nset))
    do s = 1, a%nset
      mesh%set_name(s) = 'a_' // trim(a%set_name(s))
    end do
    do s = 1, b%nset
      mesh%set_name(a%nset + s) = 'b_' // trim(b%set_name(s))
    end do
    mesh%set_start = [a%set_start(:a%nset), b%set_start + a%set_start(a%nset + 1) - 1]
    mesh%set_zone = [a%set_zone, b%set_zone + a%nzone]
    mesh%set_face = [a%set_face, b%set_face]
  end subroutine merge_meshes

  !> Names of every set of a mesh with a prefix.
  function all_sets(mesh, prefix) result(names)
    type(global_mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: prefix
    character(len=NAME_LEN), allocatable :: names(:)
    integer :: s, n
    n = 0
    do s = 1, mesh%nset
      if (index(mesh%set_name(s), prefix) == 1) n = n + 1
    end do
    allocate(names(n))
    n = 0
    do s = 1, mesh%nset
      if (index(mesh%set_name(s), prefix) == 1) then
        n = n + 1
        names(n) = mesh%set_name(s)
      end if
    end do
  end function all_sets

  subroutine make_box(lengths, zones, mesh)
    real(rk), intent(in) :: lengths(3)
    integer, intent(in) :: zones(3)
    type(global_mesh_t), intent(inout) :: mesh
    type(box_spec_t) :: spec
    type(status_t) :: status
    spec%nint = 1
    spec%breaks(1, :) = lengths
    spec%zones(1, :) = zones
    call mesh_make_box(spec, mesh, status)
    call check_true('box mesh', status%ok())
  end subroutine make_box

  ! ---------------------------------------------------------------------------
  ! References

  !> Brute force: every surface node against every segment.
  subroutine brute_force_pairs(x, slave, master, self_contact, margin, pairs)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: slave, master
    logical, intent(in) :: self_contact
    real(rk), intent(in) :: margin
    integer, allocatable, intent(out) :: pairs(:, :)
    integer :: n, s, node, npair
    integer, allocatable :: grown(:, :)
    allocate(pairs(2, 64))
    npair = 0
    do n = 1, slave%nnode
      node = slave%nodes(n)
      do s = 1, master%nseg
        if (.not. in_territory(x, master%segments(:, s), margin, node)) cycle
        if (excluded(slave, master%segments(:, s), self_contact, node)) cycle
        if (npair == size(pairs, 2)) then
          allocate(grown(2, 2 * npair))
          grown(:, :npair) = pairs
          call move_alloc(grown, pairs)
        end if
        npair = npair + 1
        pairs(:, npair) = [node, s]
      end do
    end do
    pairs = pairs(:, :npair)
  end subroutine brute_force_pairs

  logical function in_territory(x, segment, margin, node)
    real(rk), intent(in) :: x(:, :), margin
    integer(ik), intent(in) :: segment(4)
    integer, intent(in) :: node
    real(rk) :: lo(3), hi(3)
    lo = minval(x(:, segment), dim=2) - margin
    hi = maxval(x(:, segment), dim=2) + margin
    in_territory = all(x(:, node) >= lo) .and. all(x(:, node) <= hi)
  end function in_territory

  !> Exclusions, coded independently of the module: the node is a corner of the
  !> segment; in self-contact, a segment of the node shares a corner with it.
  logical function excluded(slave, segment, self_contact, node)
    type(contact_surface_t), intent(in) :: slave
    integer(ik), intent(in) :: segment(4)
    logical, intent(in) :: self_contact
    integer, intent(in) :: node
    integer :: t, i, j
    excluded = any(segment == node)
    if (excluded .or. .not. self_contact) return
    do t = 1, slave%nseg
      if (.not. any(slave%segments(:, t) == node)) cycle
      do i = 1, 4
        do j = 1, 4
          if (slave%segments(i, t) == segment(j)) excluded = .true.
        end do
      end do
    end do
  end function excluded

  !> Brute-force primary pairs: every node against every segment.
  subroutine brute_force_primary(x, slave, master, self_contact, margin, capture, depth, primary)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: slave, master
    logical, intent(in) :: self_contact
    real(rk), intent(in) :: margin, capture, depth
    type(primary_pair_t), allocatable, intent(out) :: primary(:)
    type(primary_pair_t) :: best, trial
    integer :: n, s, node, location, count_primary
    allocate(primary(slave%nnode))
    count_primary = 0
    do n = 1, slave%nnode
      node = slave%nodes(n)
      best%kind = KIND_NONE
      do s = 1, master%nseg
        if (.not. in_territory(x, master%segments(:, s), margin, node)) cycle
        if (excluded(slave, master%segments(:, s), self_contact, node)) cycle
        trial%node = node
        trial%segment = s
        call closest_point(x(:, master%segments(:, s)), x(:, node), trial%xi, trial%eta, &
            trial%gap, trial%normal, location, trial%local)
        trial%kind = contact_kind(location, trial%local, trial%gap, master%edge_convex(:, s), &
            capture, depth)
        if (trial%kind == KIND_NONE) cycle
        if (best%kind == KIND_NONE) then
          best = trial
        else if (abs(trial%gap) < abs(best%gap)) then
          best = trial
        else if (abs(trial%gap) == abs(best%gap) .and. &
            master%segment_id(s) < master%segment_id(best%segment)) then
          best = trial
        end if
      end do
      if (best%kind /= KIND_NONE) then
        count_primary = count_primary + 1
        primary(count_primary) = best
      end if
    end do
    primary = primary(:count_primary)
  end subroutine brute_force_primary

  logical function same_pairs(a, b)
    integer, intent(in) :: a(:, :), b(:, :)
    same_pairs = size(a, 2) == size(b, 2)
    if (same_pairs) same_pairs = all(a == b)
  end function same_pairs

  logical function same_primary(a, b)
    type(primary_pair_t), intent(in) :: a(:), b(:)
    integer :: i
    same_primary = size(a) == size(b)
    if (.not. same_primary) return
    do i = 1, size(a)
      same_primary = a(i)%node == b(i)%node .and. a(i)%segment == b(i)%segment .and. &
          a(i)%kind == b(i)%kind .and. a(i)%local == b(i)%local .and. a(i)%xi == b(i)%xi &
          .and. a(i)%eta == b(i)%eta .and. a(i)%gap == b(i)%gap .and. &
          all(a(i)%normal == b(i)%normal)
      if (.not. same_primary) return
    end do
  end function same_primary

  !> Bucket against brute force for one placement; returns false on a mismatch.
  logical function agree(x, slave, master, self_contact, margin, capture, depth)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: slave, master
    logical, intent(in) :: self_contact
    real(rk), intent(in) :: margin, capture, depth
    integer, allocatable :: pairs(:, :), reference(:, :)
    type(primary_pair_t), allocatable :: primary(:), reference_primary(:)
    integer :: i
    call bucket_search(x, slave, master, self_contact, margin, pairs)
    call brute_force_pairs(x, slave, master, self_contact, margin, reference)
    call primary_pairs(x, master, pairs, capture, depth, primary)
    call brute_force_primary(x, slave, master, self_contact, margin, capture, depth, &
        reference_primary)
    agree = same_pairs(pairs, reference) .and. same_primary(primary, reference_primary)
    total_cases = total_cases + 1
    total_pairs = total_pairs + size(pairs, 2)
    do i = 1, size(primary)
      count_kind(primary(i)%kind) = count_kind(primary(i)%kind) + 1
    end do
  end function agree

  ! ---------------------------------------------------------------------------
  ! Local search

  !> Planar parallelograms (bilinear = affine): Newton reproduces the analytic
  !> projection and the signed distance; beyond an edge / a corner the result
  !> is the edge / corner point.
  subroutine test_planar_projection()
    real(rk) :: r(3, 3), p(3, 4), e1(3), e2(3), origin(3), normal(3), q(3), u, v, h
    real(rk) :: xi, eta, gap, got_normal(3), worst_xi, worst_gap, worst_normal
    real(rk) :: out2(3), out3(3), distance
    integer :: trial, location, local
    logical :: located, edge_ok, corner_ok
    worst_xi = 0.0_rk
    worst_gap = 0.0_rk
    worst_normal = 0.0_rk
    located = .true.
    edge_ok = .true.
    corner_ok = .true.
    do trial = 1, 2000
      r = random_rotation(.false.)
      origin = [uniform(-5.0_rk, 5.0_rk), uniform(-5.0_rk, 5.0_rk), uniform(-5.0_rk, 5.0_rk)]
      ! Half-axes of a parallelogram in the plane z = 0, rotated.
      e1 = matmul(r, [uniform(0.2_rk, 2.0_rk), uniform(-0.3_rk, 0.3_rk), 0.0_rk])
      e2 = matmul(r, [uniform(-0.3_rk, 0.3_rk), uniform(0.2_rk, 2.0_rk), 0.0_rk])
      normal = r(:, 3)
      p(:, 1) = origin - e1 - e2
      p(:, 2) = origin + e1 - e2
      p(:, 3) = origin + e1 + e2
      p(:, 4) = origin - e1 + e2
      u = uniform(-0.99_rk, 0.99_rk)
      v = uniform(-0.99_rk, 0.99_rk)
      h = uniform(-1.0_rk, 1.0_rk)
      q = origin + u * e1 + v * e2 + h * normal
      call closest_point(p, q, xi, eta, gap, got_normal, location, local)
      located = located .and. location == LOCATION_FACE
      worst_xi = max(worst_xi, abs(xi - u), abs(eta - v))
      worst_gap = max(worst_gap, abs(gap - h))
      worst_normal = max(worst_normal, maxval(abs(got_normal - normal)))
      ! Beyond edge 2 (p2 -> p3, xi = +1), out along its in-plane outward normal.
      out2 = cross3(e2, normal)
      out2 = out2 / norm2(out2)
      out3 = cross3(-e1, normal)
      out3 = out3 / norm2(out3)
      distance = uniform(0.1_rk, 1.0_rk)
      q = origin + e1 + v * e2 + distance * out2 + h * normal
      call closest_point(p, q, xi, eta, gap, got_normal, location, local)
      edge_ok = edge_ok .and. location == LOCATION_EDGE .and. local == 2 .and. &
          xi == 1.0_rk .and. abs(eta - v) <= 1.0e-12_rk .and. &
          abs(gap - sign(hypot(distance, h), h)) <= 1.0e-12_rk
      ! Beyond corner 3, inside the cone of the outward normals of edges 2 and 3.
      q = p(:, 3) + uniform(0.05_rk, 1.0_rk) * out2 + uniform(0.05_rk, 1.0_rk) * out3 + &
          h * normal
      call closest_point(p, q, xi, eta, gap, got_normal, location, local)
      corner_ok = corner_ok .and. location == LOCATION_CORNER .and. local == 3 .and. &
          abs(gap - sign(norm2(q - p(:, 3)), h)) <= 1.0e-12_rk .and. &
          all(abs(got_normal * gap - (q - p(:, 3))) <= 1.0e-12_rk)
    end do
    call check_true('planar projection is on the face', located)
    call check_close('planar projection: natural coordinates', worst_xi, 0.0_rk, 0.0_rk, &
        atol=1.0e-11_rk)
    call check_close('planar projection: signed gap', worst_gap, 0.0_rk, 0.0_rk, &
        atol=1.0e-11_rk)
    call check_close('planar projection: normal', worst_normal, 0.0_rk, 0.0_rk, &
        atol=1.0e-12_rk)
    call check_true('beyond an edge: edge point, positive gap', edge_ok)
    call check_true('beyond a corner: corner point, signed distance', corner_ok)
  end subroutine test_planar_projection

  !> The top face of a unit box: gap > 0 above, < 0 just below (inside); a
  !> node inside the box next to the top is a penetrating segment pair.
  subroutine test_gap_sign_on_box()
    type(global_mesh_t) :: mesh
    type(contact_surface_t) :: surf
    type(status_t) :: status
    real(rk) :: xi, eta, gap, normal(3), q(3)
    integer :: location, local
    logical :: convex(4)
    call make_box([1.0_rk, 1.0_rk, 1.0_rk], [2, 2, 2], mesh)
    call surface_build(mesh, ['zmax'], surf, status)
    call check_true('zmax surface built', status%ok() .and. surf%nseg == 4 .and. surf%nnode == 9)
    ! Segment 1 covers [0, 0.5]^2 at z = 1.
    q = [0.2_rk, 0.3_rk, 1.25_rk]
    call closest_point(mesh%coordinates(:, surf%segments(:, 1)), q, xi, eta, gap, normal, &
        location, local)
    call check_close('gap above the top face', gap, 0.25_rk, 1.0e-14_rk)
    call check_true('outward normal is +z', all(abs(normal - [0.0_rk, 0.0_rk, 1.0_rk]) < &
        1.0e-14_rk))
    q = [0.2_rk, 0.3_rk, 0.9_rk]
    call closest_point(mesh%coordinates(:, surf%segments(:, 1)), q, xi, eta, gap, normal, &
        location, local)
    call check_close('gap below the top face (penetration)', gap, -0.1_rk, 1.0e-13_rk)
    convex = .true.
    call check_true('penetrating node is a segment pair', &
        contact_kind(location, local, gap, convex, 0.05_rk, 0.2_rk) == KIND_SEGMENT)
    call check_true('too deep is no pair', &
        contact_kind(location, local, gap, convex, 0.05_rk, 0.05_rk) == KIND_NONE)
    ! Interior edges of a flat face are not convex, free edges are.
    call check_true('flat interior edges not convex, free edges convex', &
        count(surf%edge_convex) == 8 .and. all(surf%edge_convex .eqv. surf%neighbours == 0))
    call surface_build(mesh, ['zmax', 'xmax'], surf, status)
    call check_true('box edge between zmax and xmax is convex', &
        count(surf%edge_convex .and. surf%neighbours /= 0) == 4)
  end subroutine test_gap_sign_on_box

  ! ---------------------------------------------------------------------------
  ! Random placements

  subroutine test_body_pairs()
    type(global_mesh_t) :: box_a, box_b, rod, tube, shell
    type(status_t) :: status
    type(rod_spec_t) :: rod_spec
    type(tube_spec_t) :: tube_spec
    type(shell_spec_t) :: shell_spec

    call make_box([1.0_rk, 1.0_rk, 1.0_rk], [4, 4, 4], box_a)
    call make_box([0.8_rk, 1.2_rk, 0.6_rk], [3, 5, 3], box_b)
    rod_spec = rod_spec_t(radius=0.6_rk, length=1.2_rk, sector='quarter', n_core=2, &
        n_radial=2, n_axial=4)
    call mesh_make_rod(rod_spec, rod, status)
    tube_spec = tube_spec_t(ri=0.4_rk, ro=0.6_rk, length=1.2_rk, sector='full', n_theta=12, &
        n_radial=1, n_axial=4)
    call mesh_make_tube(tube_spec, tube, status)
    shell_spec = shell_spec_t(ri=0.8_rk, ro=1.0_rk, n_patch=3, n_radial=1)
    call mesh_make_shell(shell_spec, shell, status)
    call check_true('curved meshes built', status%ok())
    call run_pair('box / box', box_a, box_b, 0.25_rk)
    call run_pair('box / quarter rod', box_a, rod, 0.25_rk)
    call run_pair('tube / box', tube, box_b, 0.25_rk)
    call run_pair('shell octant / box', shell, box_b, 0.3_rk)
  end subroutine test_body_pairs

  !> Random rigid placements of b relative to a: a surface node of b is put on
  !> (or near) a surface node of a, after a random rotation.
  subroutine run_pair(name, a, b, h)
    character(len=*), intent(in) :: name
    type(global_mesh_t), intent(in) :: a, b
    real(rk), intent(in) :: h !< typical segment size
    real(rk), parameter :: SCALES(6) = [0.0_rk, 0.0_rk, 0.02_rk, 0.3_rk, 1.0_rk, 4.0_rk]
    type(global_mesh_t) :: mesh
    type(contact_surface_t) :: surf_a, surf_b, relabelled
    type(status_t) :: status
    real(rk), allocatable :: x(:, :), x0(:, :)
    real(rk) :: r(3, 3), target(3), offset(3), margin, capture, depth
    integer :: trial, na, nb, i, failures, relabel_failures
    logical :: aligned

    call merge_meshes(a, b, mesh)
    call surface_build(mesh, all_sets(mesh, 'a_'), surf_a, status)
    call surface_build(mesh, all_sets(mesh, 'b_'), surf_b, status)
    call check_true(name // ': surfaces built', status%ok())
    allocate(x0, source=mesh%coordinates)
    allocate(x, source=x0)
    failures = 0
    relabel_failures = 0
    do trial = 1, CASES_PER_PAIR
      aligned = uniform(0.0_rk, 1.0_rk) < 0.3_rk
      r = random_rotation(aligned)
      na = surf_a%nodes(random_int(surf_a%nnode))
      nb = surf_b%nodes(random_int(surf_b%nnode))
      offset = SCALES(random_int(size(SCALES))) * h * [uniform(-1.0_rk, 1.0_rk), &
          uniform(-1.0_rk, 1.0_rk), uniform(-1.0_rk, 1.0_rk)]
      target = x0(:, na) + offset
      do i = a%nnode + 1, mesh%nnode
        x(:, i) = matmul(r, x0(:, i) - x0(:, nb)) + target
      end do
      call surface_update_edges(surf_a, x)
      call surface_update_edges(surf_b, x)
      margin = uniform(0.02_rk, 0.5_rk) * h
      capture = uniform(0.2_rk, 1.0_rk) * margin
      depth = uniform(0.2_rk, 2.0_rk) * h
      if (.not. agree(x, surf_a, surf_b, .false., margin, capture, depth)) failures = failures + 1
      if (.not. agree(x, surf_b, surf_a, .false., margin, capture, depth)) failures = failures + 1
      if (mod(trial, 10) == 0) then
        call relabel(x, surf_b, relabelled)
        if (.not. relabel_invariant(x, surf_a, surf_b, relabelled, margin, capture, depth)) &
            relabel_failures = relabel_failures + 1
      end if
    end do
    call check_true(name // ': bucket = brute force (pairs and primary pairs)', failures == 0)
    call check_true(name // ': pairs invariant under segment relabelling', &
        relabel_failures == 0)
    if (failures > 0) write(output_unit, '(a,i0)') '  mismatches: ', failures
  end subroutine run_pair

  !> The same surface with its segments in a random order; segment_id keeps
  !> the mapping to the original (global face ids are unique).
  subroutine relabel(x, surf, relabelled)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: surf
    type(contact_surface_t), intent(inout) :: relabelled
    integer, allocatable :: order(:)
    integer :: i
    allocate(order(surf%nseg))
    do i = 1, surf%nseg
      order(i) = i
    end do
    do i = surf%nseg, 2, -1
      call swap(order(i), order(random_int(i)))
    end do
    call surface_from_segments(surf%segments(:, order), surf%segment_id(order), x, relabelled)
  end subroutine relabel

  !> Pairs and primary pairs of slave against master and against its
  !> relabelled copy agree once segments are named by their global ids.
  logical function relabel_invariant(x, slave, master, relabelled, margin, capture, depth)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: slave, master, relabelled
    real(rk), intent(in) :: margin, capture, depth
    integer, allocatable :: pairs(:, :), pairs_relabelled(:, :)
    type(primary_pair_t), allocatable :: primary(:), primary_relabelled(:)
    integer(i8), allocatable :: key(:), key_relabelled(:)
    integer :: i
    call bucket_search(x, slave, master, .false., margin, pairs)
    call bucket_search(x, slave, relabelled, .false., margin, pairs_relabelled)
    call primary_pairs(x, master, pairs, capture, depth, primary)
    call primary_pairs(x, relabelled, pairs_relabelled, capture, depth, primary_relabelled)
    relabel_invariant = size(pairs, 2) == size(pairs_relabelled, 2) .and. &
        size(primary) == size(primary_relabelled)
    if (.not. relabel_invariant) return
    key = [(int(pairs(1, i), i8) * 2_i8**32 + master%segment_id(pairs(2, i)), &
        i = 1, size(pairs, 2))]
    key_relabelled = [(int(pairs_relabelled(1, i), i8) * 2_i8**32 + &
        relabelled%segment_id(pairs_relabelled(2, i)), i = 1, size(pairs, 2))]
    call sort_keys(key)
    call sort_keys(key_relabelled)
    relabel_invariant = all(key == key_relabelled)
    do i = 1, size(primary)
      relabel_invariant = relabel_invariant .and. primary(i)%node == primary_relabelled(i)%node &
          .and. master%segment_id(primary(i)%segment) == &
          relabelled%segment_id(primary_relabelled(i)%segment) .and. &
          primary(i)%kind == primary_relabelled(i)%kind .and. &
          primary(i)%gap == primary_relabelled(i)%gap
    end do
  end function relabel_invariant

  !> Shell sort (test sizes only).
  subroutine sort_keys(key)
    integer(i8), intent(inout) :: key(:)
    integer :: gap, i, j
    integer(i8) :: t
    gap = size(key) / 2
    do while (gap > 0)
      do i = gap + 1, size(key)
        t = key(i)
        j = i
        do while (j > gap)
          if (key(j - gap) <= t) exit
          key(j) = key(j - gap)
          j = j - gap
        end do
        key(j) = t
      end do
      gap = gap / 2
    end do
  end subroutine sort_keys

  ! ---------------------------------------------------------------------------
  ! Self-contact

  !> A thin box (s along x, thickness along y, width along z) bent into a U:
  !> two straight arms joined by a half circle, inner faces 2 R apart; random
  !> R, node jitter and rigid motion. The whole boundary is one surface.
  subroutine test_self_contact()
    real(rk), parameter :: ARM = 2.0_rk, ARC = 2.0_rk, THICK = 0.3_rk
    type(global_mesh_t) :: mesh
    type(contact_surface_t) :: surf
    type(status_t) :: status
    real(rk), allocatable :: x(:, :)
    real(rk) :: radius, s, rho, theta, point(3), r(3, 3), shift(3), margin, capture, depth
    integer :: trial, i, failures, facing
    integer, allocatable :: pairs(:, :)

    call make_box([2 * ARM + ARC, THICK, 1.0_rk], [12, 1, 2], mesh)
    call surface_build(mesh, all_sets(mesh, ''), surf, status)
    call check_true('folded surface built', status%ok() .and. surf%nseg == 2 * (12 + 24 + 2))
    allocate(x(3, mesh%nnode))
    failures = 0
    facing = 0
    do trial = 1, SELF_CASES
      radius = uniform(0.02_rk, 0.6_rk)
      r = random_rotation(uniform(0.0_rk, 1.0_rk) < 0.3_rk)
      shift = [uniform(-3.0_rk, 3.0_rk), uniform(-3.0_rk, 3.0_rk), uniform(-3.0_rk, 3.0_rk)]
      do i = 1, mesh%nnode
        s = mesh%coordinates(1, i)
        rho = radius + THICK - mesh%coordinates(2, i)
        if (s <= ARM) then
          point(1:2) = [s - ARM, -rho]
        else if (s <= ARM + ARC) then
          theta = pi * (s - ARM) / ARC
          point(1:2) = [rho * sin(theta), -rho * cos(theta)]
        else
          point(1:2) = [-(s - ARM - ARC), rho]
        end if
        point(3) = mesh%coordinates(3, i)
        point = point + 0.02_rk * [uniform(-1.0_rk, 1.0_rk), uniform(-1.0_rk, 1.0_rk), &
            uniform(-1.0_rk, 1.0_rk)]
        x(:, i) = matmul(r, point) + shift
      end do
      call surface_update_edges(surf, x)
      margin = uniform(0.05_rk, 0.5_rk)
      capture = uniform(0.2_rk, 1.0_rk) * margin
      depth = uniform(0.1_rk, 0.5_rk)
      if (.not. agree(x, surf, surf, .true., margin, capture, depth)) failures = failures + 1
      call bucket_search(x, surf, surf, .true., margin, pairs)
      if (radius < 0.1_rk .and. margin > 2 * radius + 0.05_rk) then
        if (arms_meet(mesh%coordinates, surf, pairs, ARM, ARC, THICK)) facing = facing + 1
      end if
    end do
    call check_true('self-contact: bucket = brute force (pairs and primary pairs)', failures == 0)
    call check_true('self-contact: the arms of tight folds find each other', facing > 0)
    if (failures > 0) write(output_unit, '(a,i0)') '  mismatches: ', failures
  end subroutine test_self_contact

  !> Some inner-face node of arm 1 (unbent coordinates) is paired with a
  !> segment of arm 2.
  logical function arms_meet(unbent, surf, pairs, arm, arc, thick)
    real(rk), intent(in) :: unbent(:, :)
    type(contact_surface_t), intent(in) :: surf
    integer, intent(in) :: pairs(:, :)
    real(rk), intent(in) :: arm, arc, thick
    integer :: m
    arms_meet = .false.
    do m = 1, size(pairs, 2)
      if (unbent(2, pairs(1, m)) == thick .and. unbent(1, pairs(1, m)) < arm - 0.4_rk .and. &
          all(unbent(1, surf%segments(:, pairs(2, m))) > arm + arc + 0.4_rk)) arms_meet = .true.
    end do
  end function arms_meet

end program test_contact_search
