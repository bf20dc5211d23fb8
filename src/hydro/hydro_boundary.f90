!> Boundary conditions on face sets: symmetry planes, rigid unilateral walls
!> (the set's plane, or a given plane the set reaches later), prescribed
!> velocity, applied pressure and free surfaces. Constraints act on owned nodes as
!> v <- P v + v0 (P projects onto the free directions); applied pressure is an
!> external nodal force gathered in a fixed order.
module hydro_boundary
  use core_kinds, only: rk, i8
  use core_status, only: status_t
  use mesh_geometry, only: HEX_FACE_NODES, quad_vector_area, quad_node_area_vectors
  use mesh_global, only: NAME_LEN
  use mesh_local, only: mesh_t
  use core_names, only: name_hint
  use parallel_env, only: par_rank, par_sum, par_sum_array, par_min, par_max
  use parallel_route, only: par_ordered_sum
  implicit none
  private
  public :: boundary_setup, boundary_constrain, boundary_pressure_forces, boundary_wall
  public :: boundary_prescribed

  integer, parameter, public :: BC_FREE = 0, BC_SYMMETRY = 1, BC_VELOCITY = 2, BC_PRESSURE = 3
  integer, parameter, public :: BC_WALL = 4

  !> One boundary condition as given in the deck.
  type, public :: boundary_spec_t
    character(len=NAME_LEN) :: set = '' !< face set name
    integer :: kind = BC_FREE !< BC_* code
    real(rk) :: velocity(3) = 0.0_rk !< prescribed velocity (BC_VELOCITY)
    real(rk) :: pressure = 0.0_rk !< applied pressure (BC_PRESSURE)
    !> BC_WALL given by a plane: a point of it (allocated with wall_normal)
    real(rk), allocatable :: wall_point(:)
    !> BC_WALL given by a plane: unit normal out of the wall into the body;
    !> not allocated: the wall is the set's plane at t = 0
    real(rk), allocatable :: wall_normal(:)
    !> BC_WALL: Coulomb friction coefficient (0: frictionless)
    real(rk) :: friction = 0.0_rk
  end type boundary_spec_t

  !> The conditions resolved on this rank's nodes.
  type, public :: boundary_t
    integer :: nconstrained = 0 !< owned nodes with a kinematic constraint
    integer, allocatable :: node(:) !< their local indices
    real(rk), allocatable :: projector(:, :, :) !< (3, 3, nconstrained)
    real(rk), allocatable :: value(:, :) !< (3, nconstrained) prescribed part
    integer :: nface = 0 !< local faces under applied pressure
    integer, allocatable :: face_zone(:), face_local(:) !< zone and face 1..6
    real(rk), allocatable :: face_pressure(:) !< applied pressure on each
    real(rk), allocatable :: face_force(:, :, :) !< (3, 4, nface) work space
    integer :: npnode = 0 !< owned nodes loaded by pressure faces
    integer, allocatable :: pnode(:) !< their local indices
    integer, allocatable :: pnode_start(:), pnode_list(:) !< CSR of 4 (face-1) + corner
    real(rk), allocatable :: pnode_force(:, :) !< (3, npnode) external force of the stage
    logical, allocatable :: face_symmetric(:, :) !< (6, nzone) face lies on a symmetry plane
    !> (4, n) the symmetry planes at t = 0, unit normal and offset (n . x =
    !> offset), the same on every rank (the contact audit mirrors surfaces
    !> that end on them)
    real(rk), allocatable :: symmetry_planes(:, :)
    integer :: nwall = 0 !< owned nodes of rigid-wall sets
    integer, allocatable :: wall_node(:) !< their local indices
    real(rk), allocatable :: wall_normal(:, :) !< (3, nwall) unit normal pointing into the wall
    real(rk), allocatable :: wall_offset(:) !< the wall plane: normal . x = offset
    real(rk), allocatable :: wall_tolerance(:) !< distance within which a node is on the wall
    real(rk), allocatable :: wall_friction(:) !< (nwall) Coulomb coefficient of the node's wall
    integer :: nkinematic = 0 !< owned nodes with a constraint or a wall (boundary work)
    integer, allocatable :: kinematic_node(:)
  end type boundary_t

contains

  !> Resolve the specs on the local mesh. Symmetry normals are the sums of
  !> the set's face areas in the set's global order (par_ordered_sum: every
  !> rank count gives the same bits); a symmetry set must be planar.
  !> coordinates: the local nodes' initial positions.
  subroutine boundary_setup(specs, mesh, coordinates, bc, status)
    type(boundary_spec_t), intent(in) :: specs(:)
    type(mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: coordinates(:, :) !< (3, mesh%nnode)
    type(boundary_t), intent(inout) :: bc
    type(status_t), intent(inout) :: status
    real(rk), allocatable :: dir(:, :, :), target(:, :), normal(:, :), areas(:, :)
    integer(i8), allocatable :: keys(:)
    integer, allocatable :: ndir(:), slot(:)
    integer :: ib, s, f, k, n, i, j, nowned, bad
    real(rk) :: area(3), p(3, 4), total(3), d(3), tval, len_d, first(3)
    character(len=16) :: text

    nowned = mesh%nnode_owned
    allocate(normal(3, size(specs)))
    normal = 0.0_rk
    ! Set normals (ordered global sums, so every rank agrees) and planarity.
    do ib = 1, size(specs)
      s = set_index(mesh, specs(ib)%set)
      if (s == 0) then
        write(text, '(i0)') ib
        call status%add('&boundary('//trim(text)//'): set: '''//trim(specs(ib)%set)// &
            ''' is not a face set of the mesh'//name_hint(specs(ib)%set, &
            mesh%set_name(1:mesh%nset)))
        cycle
      end if
      if (specs(ib)%kind /= BC_SYMMETRY .and. specs(ib)%kind /= BC_WALL) cycle
      if (specs(ib)%kind == BC_WALL .and. allocated(specs(ib)%wall_normal)) then
        ! A given plane: the set may be curved, but must start on the body side.
        normal(:, ib) = -specs(ib)%wall_normal
        call check_wall_side(ib, s)
        cycle
      end if
      n = count(mesh%set_zone(mesh%set_start(s):mesh%set_start(s + 1) - 1) <= mesh%nzone_owned)
      allocate(keys(n), areas(3, n))
      n = 0
      do f = mesh%set_start(s), mesh%set_start(s + 1) - 1
        if (mesh%set_zone(f) > mesh%nzone_owned) cycle
        n = n + 1
        keys(n) = mesh%set_ord(f)
        areas(:, n) = quad_vector_area(face_points(f))
      end do
      call par_ordered_sum(keys, areas, total)
      deallocate(keys, areas)
      if (norm2(total) <= 0.0_rk) then
        write(text, '(i0)') ib
        call status%add('&boundary('//trim(text)//'): set: '''//trim(specs(ib)%set)// &
            ''' has no area, so it cannot be a symmetry plane')
        cycle
      end if
      normal(:, ib) = total / norm2(total)
      bad = 0
      do f = mesh%set_start(s), mesh%set_start(s + 1) - 1
        area = quad_vector_area(face_points(f))
        if (dot_product(area, normal(:, ib)) < (1.0_rk - 1.0e-10_rk) * norm2(area)) bad = 1
      end do
      if (par_max(bad) > 0) then
        write(text, '(i0)') ib
        call status%add('&boundary('//trim(text)//'): type: '''//trim(kind_name(specs(ib)%kind)) &
            //''' needs a plane, but set '''//trim(specs(ib)%set)//''' is not planar')
      end if
    end do
    if (.not. status%ok()) return
    allocate(bc%symmetry_planes(4, count(specs%kind == BC_SYMMETRY)))
    j = 0
    do ib = 1, size(specs)
      if (specs(ib)%kind /= BC_SYMMETRY) cycle
      ! The first node of the set's first face, from the rank that owns it.
      s = set_index(mesh, specs(ib)%set)
      first = 0.0_rk
      do f = mesh%set_start(s), mesh%set_start(s + 1) - 1
        if (mesh%set_ord(f) == 1 .and. mesh%set_zone(f) <= mesh%nzone_owned) then
          p = face_points(f)
          first = p(:, 1)
        end if
      end do
      call par_sum_array(first)
      j = j + 1
      bc%symmetry_planes(:, j) = [normal(:, ib), dot_product(normal(:, ib), first)]
    end do

    ! Kinematic constraints: velocity directions first, then symmetry normals.
    allocate(dir(3, 3, nowned), target(3, nowned), ndir(nowned))
    ndir = 0
    do j = 1, 2
      do ib = 1, size(specs)
        if (j == 1 .and. specs(ib)%kind /= BC_VELOCITY) cycle
        if (j == 2 .and. specs(ib)%kind /= BC_SYMMETRY) cycle
        s = set_index(mesh, specs(ib)%set)
        do f = mesh%set_start(s), mesh%set_start(s + 1) - 1
          do k = 1, 4
            n = mesh%zone_node(HEX_FACE_NODES(k, mesh%set_face(f)), mesh%set_zone(f))
            if (n > nowned) cycle
            if (j == 1) then
              do i = 1, 3
                d = 0.0_rk
                d(i) = 1.0_rk
                call add_direction(n, d, specs(ib)%velocity(i))
              end do
            else
              call add_direction(n, normal(:, ib), 0.0_rk)
            end if
          end do
        end do
      end do
    end do
    bc%nconstrained = count(ndir > 0)
    allocate(bc%node(bc%nconstrained), bc%projector(3, 3, bc%nconstrained))
    allocate(bc%value(3, bc%nconstrained))
    k = 0
    do n = 1, nowned
      if (ndir(n) == 0) cycle
      k = k + 1
      bc%node(k) = n
      bc%projector(:, :, k) = 0.0_rk
      bc%value(:, k) = 0.0_rk
      do i = 1, 3
        bc%projector(i, i, k) = 1.0_rk
      end do
      do i = 1, ndir(n)
        do j = 1, 3
          bc%projector(:, j, k) = bc%projector(:, j, k) - dir(:, i, n) * dir(j, i, n)
        end do
        bc%value(:, k) = bc%value(:, k) + target(i, n) * dir(:, i, n)
      end do
    end do

    allocate(bc%face_symmetric(6, mesh%nzone))
    bc%face_symmetric = .false.
    do ib = 1, size(specs)
      if (specs(ib)%kind /= BC_SYMMETRY) cycle
      s = set_index(mesh, specs(ib)%set)
      do f = mesh%set_start(s), mesh%set_start(s + 1) - 1
        bc%face_symmetric(mesh%set_face(f), mesh%set_zone(f)) = .true.
      end do
    end do

    ! Rigid walls: the plane of the set at t = 0; its owned nodes.
    call setup_walls()

    ! Applied pressure: local faces, and the owned nodes they load.
    bc%nface = 0
    do ib = 1, size(specs)
      if (specs(ib)%kind /= BC_PRESSURE) cycle
      s = set_index(mesh, specs(ib)%set)
      bc%nface = bc%nface + mesh%set_start(s + 1) - mesh%set_start(s)
    end do
    allocate(bc%face_zone(bc%nface), bc%face_local(bc%nface), bc%face_pressure(bc%nface))
    allocate(bc%face_force(3, 4, bc%nface))
    allocate(slot(max(1, mesh%nnode)))
    slot = 0
    i = 0
    do ib = 1, size(specs)
      if (specs(ib)%kind /= BC_PRESSURE) cycle
      s = set_index(mesh, specs(ib)%set)
      do f = mesh%set_start(s), mesh%set_start(s + 1) - 1
        i = i + 1
        bc%face_zone(i) = mesh%set_zone(f)
        bc%face_local(i) = mesh%set_face(f)
        bc%face_pressure(i) = specs(ib)%pressure
        do k = 1, 4
          n = mesh%zone_node(HEX_FACE_NODES(k, mesh%set_face(f)), mesh%set_zone(f))
          if (n <= nowned) slot(n) = slot(n) + 1
        end do
      end do
    end do
    bc%npnode = count(slot > 0)
    allocate(bc%pnode(bc%npnode), bc%pnode_start(bc%npnode + 1))
    allocate(bc%pnode_list(max(1, sum(slot))), bc%pnode_force(3, bc%npnode))
    k = 0
    bc%pnode_start(1) = 1
    do n = 1, mesh%nnode
      if (slot(n) == 0) cycle
      k = k + 1
      bc%pnode(k) = n
      bc%pnode_start(k + 1) = bc%pnode_start(k) + slot(n)
      slot(n) = k
    end do
    ! Fill in face order (global set order), so every rank sums alike.
    deallocate(ndir)
    allocate(ndir(max(1, bc%npnode)))
    ndir = 0
    do i = 1, bc%nface
      do k = 1, 4
        n = mesh%zone_node(HEX_FACE_NODES(k, bc%face_local(i)), bc%face_zone(i))
        if (n > nowned) cycle
        j = slot(n)
        bc%pnode_list(bc%pnode_start(j) + ndir(j)) = 4 * (i - 1) + k
        ndir(j) = ndir(j) + 1
      end do
    end do

  contains

    !> A wall given by a plane: every node of set s must be on the body side of
    !> it (or on it, within 1e-9 of the set's extent) at t = 0.
    subroutine check_wall_side(ispec, s)
      integer, intent(in) :: ispec !< index of the &boundary group
      integer, intent(in) :: s !< its local face set
      integer :: ff, kk, nbeyond, cc
      real(rk) :: pts(3, 4), lo(3), hi(3), offset, depth, worst, at(3), gworst
      logical, allocatable :: beyond(:)
      character(len=200) :: detail
      offset = dot_product(normal(:, ispec), specs(ispec)%wall_point)
      lo = huge(1.0_rk)
      hi = -huge(1.0_rk)
      do ff = mesh%set_start(s), mesh%set_start(s + 1) - 1
        pts = face_points(ff)
        lo = min(lo, minval(pts, dim=2))
        hi = max(hi, maxval(pts, dim=2))
      end do
      do cc = 1, 3
        lo(cc) = par_min(lo(cc))
        hi(cc) = par_max(hi(cc))
      end do
      ! Owned nodes only: each node is counted by its owner, which holds
      ! every zone around it.
      allocate(beyond(mesh%nnode))
      beyond = .false.
      worst = 0.0_rk
      at = 0.0_rk
      do ff = mesh%set_start(s), mesh%set_start(s + 1) - 1
        pts = face_points(ff)
        do kk = 1, 4
          depth = dot_product(normal(:, ispec), pts(:, kk)) - offset
          if (depth <= 1.0e-9_rk * norm2(hi - lo)) cycle
          cc = mesh%zone_node(HEX_FACE_NODES(kk, mesh%set_face(ff)), mesh%set_zone(ff))
          if (cc <= nowned) beyond(cc) = .true.
          if (depth > worst) then
            worst = depth
            at = pts(:, kk)
          end if
        end do
      end do
      nbeyond = par_sum(count(beyond))
      if (nbeyond == 0) return
      gworst = par_max(worst)
      ! The farthest point, from the lowest rank that holds it.
      cc = par_min(merge(par_rank(), huge(1), worst == gworst))
      if (par_rank() /= cc) at = 0.0_rk
      call par_sum_array(at)
      write(text, '(i0)') ispec
      write(detail, '(i0,a,3(1x,es12.5),a,es10.3)') nbeyond, ' node(s) of set '''// &
          trim(specs(ispec)%set)//''' start beyond the wall plane, the farthest (', at, &
          ') by', gworst
      call status%add('&boundary('//trim(text)//'): wall_point: '//trim(detail)// &
          ' cm (the set must start on the body side; wall_normal points out of the '// &
          'wall into the body)')
    end subroutine check_wall_side

    subroutine setup_walls()
      integer :: iw, sg, ff, kk, nn, count_wall
      real(rk) :: offset, extent(3, 2), pts(3, 4)
      logical, allocatable :: is_wall(:), is_kin(:)
      real(rk), allocatable :: nrm(:, :), off(:), tol(:), fric(:)
      allocate(is_wall(nowned), nrm(3, nowned), off(nowned), tol(nowned), is_kin(nowned), &
          fric(nowned))
      is_wall = .false.
      do iw = 1, size(specs)
        if (specs(iw)%kind /= BC_WALL) cycle
        sg = set_index(mesh, specs(iw)%set)
        offset = -huge(1.0_rk)
        if (allocated(specs(iw)%wall_normal)) offset = dot_product(normal(:, iw), &
            specs(iw)%wall_point)
        extent(:, 1) = huge(1.0_rk)
        extent(:, 2) = -huge(1.0_rk)
        do ff = mesh%set_start(sg), mesh%set_start(sg + 1) - 1
          pts = face_points(ff)
          if (.not. allocated(specs(iw)%wall_normal)) offset = max(offset, &
              maxval(matmul(normal(:, iw), pts)))
          extent(:, 1) = min(extent(:, 1), minval(pts, dim=2))
          extent(:, 2) = max(extent(:, 2), maxval(pts, dim=2))
        end do
        offset = par_max(offset)
        do kk = 1, 3
          extent(kk, 1) = par_min(extent(kk, 1))
          extent(kk, 2) = par_max(extent(kk, 2))
        end do
        sg = set_index(mesh, specs(iw)%set)
        do ff = mesh%set_start(sg), mesh%set_start(sg + 1) - 1
          do kk = 1, 4
            nn = mesh%zone_node(HEX_FACE_NODES(kk, mesh%set_face(ff)), mesh%set_zone(ff))
            if (nn > nowned) cycle
            is_wall(nn) = .true.
            nrm(:, nn) = normal(:, iw)
            off(nn) = offset
            tol(nn) = 1.0e-9_rk * norm2(extent(:, 2) - extent(:, 1))
            fric(nn) = specs(iw)%friction
          end do
        end do
      end do
      count_wall = count(is_wall)
      bc%nwall = count_wall
      allocate(bc%wall_node(count_wall), bc%wall_normal(3, count_wall))
      allocate(bc%wall_offset(count_wall), bc%wall_tolerance(count_wall), &
          bc%wall_friction(count_wall))
      kk = 0
      do nn = 1, nowned
        if (.not. is_wall(nn)) cycle
        kk = kk + 1
        bc%wall_node(kk) = nn
        bc%wall_normal(:, kk) = nrm(:, nn)
        bc%wall_offset(kk) = off(nn)
        bc%wall_tolerance(kk) = tol(nn)
        bc%wall_friction(kk) = fric(nn)
      end do
      is_kin = is_wall
      is_kin(bc%node(1:bc%nconstrained)) = .true.
      bc%nkinematic = count(is_kin)
      bc%kinematic_node = pack([(nn, nn = 1, nowned)], is_kin)
    end subroutine setup_walls

    !> The corner positions of local set face ff.
    function face_points(ff) result(pts)
      integer, intent(in) :: ff
      real(rk) :: pts(3, 4)
      pts = coordinates(:, mesh%zone_node(HEX_FACE_NODES(:, mesh%set_face(ff)), mesh%set_zone(ff)))
    end function face_points

    subroutine add_direction(node, dvec, value)
      integer, intent(in) :: node
      real(rk), intent(in) :: dvec(3), value
      integer :: m
      d = dvec
      tval = value
      do m = 1, ndir(node)
        tval = tval - dot_product(dvec, dir(:, m, node)) * target(m, node)
        d = d - dot_product(dvec, dir(:, m, node)) * dir(:, m, node)
      end do
      len_d = norm2(d)
      if (len_d < 1.0e-8_rk .or. ndir(node) == 3) return
      ndir(node) = ndir(node) + 1
      dir(:, ndir(node), node) = d / len_d
      target(ndir(node), node) = tval / len_d
    end subroutine add_direction

  end subroutine boundary_setup

  function kind_name(kind) result(name)
    integer, intent(in) :: kind
    character(len=16) :: name
    select case (kind)
    case (BC_SYMMETRY)
      name = 'symmetry'
    case (BC_WALL)
      name = 'wall'
    case default
      name = 'other'
    end select
  end function kind_name

  !> Rigid unilateral walls: a node whose free motion over the step (from x
  !> with the trapezoid of v_old and its new velocity v) would end beyond the
  !> wall, and whose new velocity points into it, loses that normal component;
  !> a node pulled away (tension) is free to leave, and one approaching is held
  !> on the step it would cross (no penetration beyond the half step of the
  !> impact). The same closing rule as the contact methods, so that a body
  !> hitting its mirror image through contact equals the body on the wall.
  !> Coulomb friction (friction = mu > 0): a node held by the wall loses the
  !> normal velocity vn (the normal impulse per unit mass), and its tangential
  !> velocity vt (the wall is at rest) is reduced toward 0 by at most mu vn:
  !> stopped when |vt| <= mu vn (stick), else by mu vn against vt (slip).
  !> With mu = 0 none of it runs (results bitwise those without friction).
  subroutine boundary_wall(bc, x, v_old, v, step)
    type(boundary_t), intent(in) :: bc
    real(rk), intent(in) :: x(:, :) !< positions at the start of the step
    real(rk), intent(in) :: v_old(:, :) !< velocities at the start of the step
    real(rk), intent(inout) :: v(:, :) !< new velocities
    real(rk), intent(in) :: step
    integer :: k, n
    real(rk) :: vn, vt(3), speed, limit
    do k = 1, bc%nwall
      n = bc%wall_node(k)
      vn = dot_product(bc%wall_normal(:, k), v(:, n))
      if (.not. vn > 0.0_rk) cycle
      if (.not. dot_product(bc%wall_normal(:, k), x(:, n) + 0.5_rk * step * &
          (v_old(:, n) + v(:, n))) > bc%wall_offset(k)) cycle
      v(:, n) = v(:, n) - vn * bc%wall_normal(:, k)
      if (.not. bc%wall_friction(k) > 0.0_rk) cycle
      vt = v(:, n) - dot_product(bc%wall_normal(:, k), v(:, n)) * bc%wall_normal(:, k)
      speed = norm2(vt)
      limit = bc%wall_friction(k) * vn
      if (speed > limit) then
        v(:, n) = v(:, n) - (limit / speed) * vt
      else
        v(:, n) = v(:, n) - vt
      end if
    end do
  end subroutine boundary_wall

  integer function set_index(mesh, name) result(s)
    type(mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: name
    do s = 1, mesh%nset
      if (trim(mesh%set_name(s)) == trim(name)) return
    end do
    s = 0
  end function set_index

  !> Local nodes whose motion is prescribed in every direction (a velocity
  !> set: no free direction left by the constraint), for the contact, which
  !> treats them as rigid.
  function boundary_prescribed(bc, nnode) result(fixed)
    type(boundary_t), intent(in) :: bc
    integer, intent(in) :: nnode !< local nodes
    logical :: fixed(nnode)
    integer :: k
    fixed = .false.
    do k = 1, bc%nconstrained
      fixed(bc%node(k)) = all(bc%projector(:, :, k) == 0.0_rk)
    end do
  end function boundary_prescribed

  !> Impose the kinematic constraints on a velocity (or acceleration, with
  !> with_value = .false.) field of the owned nodes.
  subroutine boundary_constrain(bc, v, with_value)
    type(boundary_t), intent(in) :: bc
    real(rk), intent(inout) :: v(:, :)
    logical, intent(in) :: with_value
    integer :: k, n
    real(rk) :: w(3)
    do k = 1, bc%nconstrained
      n = bc%node(k)
      w = matmul(bc%projector(:, :, k), v(:, n))
      if (with_value) w = w + bc%value(:, k)
      v(:, n) = w
    end do
  end subroutine boundary_constrain

  !> Add the applied-pressure forces at positions x to the owned node forces,
  !> keeping the external part in bc%pnode_force.
  subroutine boundary_pressure_forces(bc, mesh, x, force)
    type(boundary_t), intent(inout) :: bc
    type(mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: x(:, :)
    real(rk), intent(inout) :: force(:, :)
    integer :: i, k, j, c
    real(rk) :: p(3, 4), a(3, 4), f(3)
    do i = 1, bc%nface
      do k = 1, 4
        p(:, k) = x(:, mesh%zone_node(HEX_FACE_NODES(k, bc%face_local(i)), bc%face_zone(i)))
      end do
      call quad_node_area_vectors(p, a)
      bc%face_force(:, :, i) = -bc%face_pressure(i) * a
    end do
    do j = 1, bc%npnode
      f = 0.0_rk
      do c = bc%pnode_start(j), bc%pnode_start(j + 1) - 1
        i = (bc%pnode_list(c) - 1) / 4 + 1
        k = mod(bc%pnode_list(c) - 1, 4) + 1
        f = f + bc%face_force(:, k, i)
      end do
      bc%pnode_force(:, j) = f
      force(:, bc%pnode(j)) = force(:, bc%pnode(j)) + f
    end do
  end subroutine boundary_pressure_forces

end module hydro_boundary
