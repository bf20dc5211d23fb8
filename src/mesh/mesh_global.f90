!> The whole mesh as generated or read, before partitioning: every rank builds
!> the same one (deterministic), then keeps its part (mesh_local).
module mesh_global
  use core_kinds, only: rk, ik, i8
  use core_status, only: status_t
  implicit none
  private
  public :: box_spec_t, mesh_make_box, interval_points, mesh_append, box_position

  integer, parameter, public :: MAX_INTERVALS = 16
  integer, parameter, public :: NAME_LEN = 32

  !> Global hex mesh: 1-based node ids in connectivity, zones in global-id order.
  type, public :: global_mesh_t
    integer :: nnode = 0 !< nodes
    integer :: nzone = 0 !< zones
    real(rk), allocatable :: coordinates(:, :) !< (3, nnode)
    integer(ik), allocatable :: connectivity(:, :) !< (8, nzone)
    integer(ik), allocatable :: zone_block(:) !< block index of each zone (0 = none yet)
    integer :: nset = 0 !< named face sets
    character(len=NAME_LEN), allocatable :: set_name(:) !< their names
    integer, allocatable :: set_start(:) !< CSR into set_zone/set_face, size nset+1
    integer(ik), allocatable :: set_zone(:) !< zone of each set face
    integer(ik), allocatable :: set_face(:) !< local face 1..6 (mesh_geometry order)
  contains
    procedure :: free => global_mesh_free
    procedure :: find_set => global_mesh_find_set
  end type global_mesh_t

  !> A structured box: per direction, breakpoints, zones per interval and grading.
  type :: box_spec_t
    integer :: nint(3) = 0 !< intervals per direction
    real(rk) :: breaks(0:MAX_INTERVALS, 3) = 0.0_rk !< interval end points
    integer :: zones(MAX_INTERVALS, 3) = 0 !< zones in each interval
    real(rk) :: ratio(MAX_INTERVALS, 3) = 1.0_rk !< last/first zone size in each interval
    real(rk) :: skew_amplitude = 0.0_rk !< Saltzman sine skew of x (0 = none)
    real(rk) :: perturb = 0.0_rk !< random interior-node displacement, fraction of zone size
  end type box_spec_t

contains

  !> Release everything.
  subroutine global_mesh_free(this)
    class(global_mesh_t), intent(inout) :: this
    if (allocated(this%coordinates)) deallocate(this%coordinates)
    if (allocated(this%connectivity)) deallocate(this%connectivity)
    if (allocated(this%zone_block)) deallocate(this%zone_block)
    if (allocated(this%set_name)) deallocate(this%set_name)
    if (allocated(this%set_start)) deallocate(this%set_start)
    if (allocated(this%set_zone)) deallocate(this%set_zone)
    if (allocated(this%set_face)) deallocate(this%set_face)
    this%nnode = 0
    this%nzone = 0
    this%nset = 0
  end subroutine global_mesh_free

  !> Index of the face set called name, 0 if there is none.
  integer function global_mesh_find_set(this, name) result(k)
    class(global_mesh_t), intent(in) :: this
    character(len=*), intent(in) :: name
    do k = 1, this%nset
      if (trim(this%set_name(k)) == trim(name)) return
    end do
    k = 0
  end function global_mesh_find_set

  !> Node positions along one direction: geometric grading in each interval.
  subroutine interval_points(nint, breaks, zones, ratio, points)
    integer, intent(in) :: nint
    real(rk), intent(in) :: breaks(0:), ratio(:)
    integer, intent(in) :: zones(:)
    real(rk), allocatable, intent(out) :: points(:) !< 0:n positions
    integer :: i, k, n, pos
    real(rk) :: q, first, length, s
    n = sum(zones(1:nint))
    allocate(points(0:n))
    points(0) = breaks(0)
    pos = 0
    do i = 1, nint
      length = breaks(i) - breaks(i - 1)
      if (zones(i) == 1 .or. abs(ratio(i) - 1.0_rk) < 1.0e-14_rk) then
        do k = 1, zones(i)
          points(pos + k) = breaks(i - 1) + length * real(k, rk) / real(zones(i), rk)
        end do
      else
        q = ratio(i)**(1.0_rk / real(zones(i) - 1, rk))
        first = length * (q - 1.0_rk) / (q**zones(i) - 1.0_rk)
        s = 0.0_rk
        do k = 1, zones(i)
          s = s + first * q**(k - 1)
          points(pos + k) = breaks(i - 1) + s
        end do
      end if
      points(pos + zones(i)) = breaks(i)
      pos = pos + zones(i)
    end do
  end subroutine interval_points

  !> Structured box with face sets xmin, xmax, ymin, ymax, zmin, zmax.
  !> Node (i,j,k) has id i + (nx+1) j + (nx+1)(ny+1) k + 1 (0-based i,j,k);
  !> zone ids run the same way with i fastest.
  subroutine mesh_make_box(spec, mesh, status)
    type(box_spec_t), intent(in) :: spec
    type(global_mesh_t), intent(inout) :: mesh
    type(status_t), intent(inout) :: status
    real(rk), allocatable :: px(:), py(:), pz(:)
    integer :: nx, ny, nz, i, j, k, z, s, f, count_face

    call mesh%free()
    call interval_points(spec%nint(1), spec%breaks(:, 1), spec%zones(:, 1), spec%ratio(:, 1), px)
    call interval_points(spec%nint(2), spec%breaks(:, 2), spec%zones(:, 2), spec%ratio(:, 2), py)
    call interval_points(spec%nint(3), spec%breaks(:, 3), spec%zones(:, 3), spec%ratio(:, 3), pz)
    nx = size(px) - 1
    ny = size(py) - 1
    nz = size(pz) - 1
    if (nx < 1 .or. ny < 1 .or. nz < 1) then
      call status%add('&mesh: the box needs at least one zone in each direction')
      return
    end if
    mesh%nnode = (nx + 1) * (ny + 1) * (nz + 1)
    mesh%nzone = nx * ny * nz
    allocate(mesh%coordinates(3, mesh%nnode), mesh%connectivity(8, mesh%nzone))
    allocate(mesh%zone_block(mesh%nzone))
    mesh%zone_block = 0
    do k = 0, nz
      do j = 0, ny
        do i = 0, nx
          mesh%coordinates(:, node_id(i, j, k)) = box_position(spec, px, py, pz, i, j, k)
        end do
      end do
    end do
    do k = 0, nz - 1
      do j = 0, ny - 1
        do i = 0, nx - 1
          z = 1 + i + nx * (j + ny * k)
          mesh%connectivity(:, z) = [node_id(i, j, k), node_id(i + 1, j, k), &
              node_id(i + 1, j + 1, k), node_id(i, j + 1, k), node_id(i, j, k + 1), &
              node_id(i + 1, j, k + 1), node_id(i + 1, j + 1, k + 1), node_id(i, j + 1, k + 1)]
        end do
      end do
    end do
    ! Face sets; mesh_geometry face order: 1 zeta-, 2 zeta+, 3 eta-, 4 xi+, 5 eta+, 6 xi-.
    mesh%nset = 6
    allocate(mesh%set_name(6), mesh%set_start(7))
    mesh%set_name = [character(len=NAME_LEN) :: 'xmin', 'xmax', 'ymin', 'ymax', 'zmin', 'zmax']
    count_face = 2 * (ny * nz + nx * nz + nx * ny)
    allocate(mesh%set_zone(count_face), mesh%set_face(count_face))
    s = 0
    mesh%set_start(1) = 1
    do f = 1, 6
      do k = 0, nz - 1
        do j = 0, ny - 1
          do i = 0, nx - 1
            if (on_face(f, i, j, k)) then
              s = s + 1
              mesh%set_zone(s) = 1 + i + nx * (j + ny * k)
              mesh%set_face(s) = face_of_set(f)
            end if
          end do
        end do
      end do
      mesh%set_start(f + 1) = s + 1
    end do

  contains

    pure integer function node_id(ii, jj, kk)
      integer, intent(in) :: ii, jj, kk
      node_id = 1 + ii + (nx + 1) * (jj + (ny + 1) * kk)
    end function node_id

    pure logical function on_face(set, ii, jj, kk)
      integer, intent(in) :: set, ii, jj, kk
      select case (set)
      case (1)
        on_face = ii == 0
      case (2)
        on_face = ii == nx - 1
      case (3)
        on_face = jj == 0
      case (4)
        on_face = jj == ny - 1
      case (5)
        on_face = kk == 0
      case default
        on_face = kk == nz - 1
      end select
    end function on_face

    pure integer function face_of_set(set)
      integer, intent(in) :: set
      integer, parameter :: map(6) = [6, 4, 3, 5, 1, 2]
      face_of_set = map(set)
    end function face_of_set

  end subroutine mesh_make_box

  !> The position of box node (i, j, k) (0-based) on the interval points
  !> px, py, pz: the Saltzman skew of x, then the perturbation of interior
  !> nodes (deterministic in the node id). Every box generator uses it, so
  !> whole and distributed boxes agree bit for bit.
  pure function box_position(spec, px, py, pz, i, j, k) result(x)
    type(box_spec_t), intent(in) :: spec
    real(rk), intent(in) :: px(0:), py(0:), pz(0:)
    integer, intent(in) :: i, j, k
    real(rk) :: x(3)
    integer :: nx, ny, nz, n
    real(rk) :: pi
    nx = ubound(px, 1)
    ny = ubound(py, 1)
    nz = ubound(pz, 1)
    x = [px(i), py(j), pz(k)]
    if (spec%skew_amplitude /= 0.0_rk) then
      pi = acos(-1.0_rk)
      x(1) = px(i) + spec%skew_amplitude * (py(ny) - py(j)) / &
          (py(ny) - py(0)) * sin(pi * (px(i) - px(0)) / (px(nx) - px(0)))
    end if
    ! Interior nodes only, so the faces stay planar.
    if (spec%perturb > 0.0_rk .and. i > 0 .and. i < nx .and. j > 0 .and. j < ny &
        .and. k > 0 .and. k < nz) then
      n = 1 + i + (nx + 1) * (j + (ny + 1) * k)
      x = x + spec%perturb * &
          [min(px(i) - px(i - 1), px(i + 1) - px(i)) * unit_hash(n, 1), &
          min(py(j) - py(j - 1), py(j + 1) - py(j)) * unit_hash(n, 2), &
          min(pz(k) - pz(k - 1), pz(k + 1) - pz(k)) * unit_hash(n, 3)]
    end if
  end function box_position

  !> A number in [-0.5, 0.5) from a node id and a component (integer hash).
  pure real(rk) function unit_hash(id, comp)
    integer, intent(in) :: id, comp
    integer(i8) :: h
    h = int(id, i8) * 2654435761_i8 + int(comp, i8) * 40503_i8
    h = modulo(ieor(h, ishft(h, -13)), 2147483648_i8)
    h = modulo(h * 1103515245_i8 + 12345_i8, 2147483648_i8)
    unit_hash = real(h, rk) / 2147483648.0_rk - 0.5_rk
  end function unit_hash

  !> Append the mesh part to mesh (nodes, zones and face sets renumbered after
  !> those already there; parts stay disconnected, sharing no node). Each face
  !> set of the part joins the set of the same name (created if new), so that
  !> e.g. 'ymin' names the y = min faces of every part; when prefix is given
  !> the part's faces also form the set prefix_name (e.g. 'bar1_xmax'), which
  !> is how a contact surface names one body. Zone blocks are kept.
  subroutine mesh_append(mesh, part, prefix)
    type(global_mesh_t), intent(inout) :: mesh
    type(global_mesh_t), intent(in) :: part
    character(len=*), intent(in) :: prefix !< '' = no prefixed sets
    character(len=NAME_LEN), allocatable :: names(:)
    integer, allocatable :: start(:), fill(:)
    integer(ik), allocatable :: zone(:), face(:)
    real(rk), allocatable :: x(:, :)
    integer(ik), allocatable :: conn(:, :), block(:)
    integer :: nname, k, j, i, nface, p, new_set

    ! Set names of the result: mesh's, then the part's new plain names, then
    ! its prefixed names.
    nname = mesh%nset
    allocate(names(mesh%nset + 2 * part%nset))
    if (mesh%nset > 0) names(:mesh%nset) = mesh%set_name(:mesh%nset)
    do k = 1, part%nset
      if (.not. any(names(:nname) == part%set_name(k))) then
        nname = nname + 1
        names(nname) = part%set_name(k)
      end if
    end do
    if (len_trim(prefix) > 0) then
      do k = 1, part%nset
        nname = nname + 1
        names(nname) = trim(prefix) // '_' // trim(part%set_name(k))
      end do
    end if

    ! Count faces per result set, then fill (old faces first, in order).
    allocate(start(nname + 1), fill(nname))
    start = 0
    do k = 1, mesh%nset
      start(k + 1) = mesh%set_start(k + 1) - mesh%set_start(k)
    end do
    do k = 1, part%nset
      nface = part%set_start(k + 1) - part%set_start(k)
      j = findloc(names(:nname), part%set_name(k), dim=1)
      start(j + 1) = start(j + 1) + nface
      if (len_trim(prefix) > 0) then
        j = findloc(names(:nname), trim(prefix) // '_' // trim(part%set_name(k)), dim=1)
        start(j + 1) = start(j + 1) + nface
      end if
    end do
    start(1) = 1
    do k = 1, nname
      start(k + 1) = start(k + 1) + start(k)
    end do
    allocate(zone(start(nname + 1) - 1), face(start(nname + 1) - 1))
    fill = start(:nname)
    do k = 1, mesh%nset
      do i = mesh%set_start(k), mesh%set_start(k + 1) - 1
        zone(fill(k)) = mesh%set_zone(i)
        face(fill(k)) = mesh%set_face(i)
        fill(k) = fill(k) + 1
      end do
    end do
    do k = 1, part%nset
      do p = 1, 2
        if (p == 1) then
          new_set = findloc(names(:nname), part%set_name(k), dim=1)
        else
          if (len_trim(prefix) == 0) exit
          new_set = findloc(names(:nname), trim(prefix) // '_' // trim(part%set_name(k)), dim=1)
        end if
        do i = part%set_start(k), part%set_start(k + 1) - 1
          zone(fill(new_set)) = part%set_zone(i) + int(mesh%nzone, ik)
          face(fill(new_set)) = part%set_face(i)
          fill(new_set) = fill(new_set) + 1
        end do
      end do
    end do

    allocate(x(3, mesh%nnode + part%nnode), conn(8, mesh%nzone + part%nzone))
    allocate(block(mesh%nzone + part%nzone))
    if (mesh%nnode > 0) x(:, :mesh%nnode) = mesh%coordinates
    x(:, mesh%nnode + 1:) = part%coordinates
    if (mesh%nzone > 0) then
      conn(:, :mesh%nzone) = mesh%connectivity
      block(:mesh%nzone) = mesh%zone_block
    end if
    conn(:, mesh%nzone + 1:) = part%connectivity + int(mesh%nnode, ik)
    block(mesh%nzone + 1:) = part%zone_block
    call move_alloc(x, mesh%coordinates)
    call move_alloc(conn, mesh%connectivity)
    call move_alloc(block, mesh%zone_block)
    mesh%nnode = mesh%nnode + part%nnode
    mesh%nzone = mesh%nzone + part%nzone
    mesh%nset = nname
    names = names(:nname)
    call move_alloc(names, mesh%set_name)
    call move_alloc(start, mesh%set_start)
    call move_alloc(zone, mesh%set_zone)
    call move_alloc(face, mesh%set_face)
  end subroutine mesh_append

end module mesh_global
