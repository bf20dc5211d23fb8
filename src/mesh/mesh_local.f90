!> This rank's part of the mesh: owned zones plus one layer of ghost zones
!> (every zone sharing a node with an owned zone), their nodes, the node ->
!> corner lists that make the force gather independent of the rank count, and
!> the halo and I/O plans.
module mesh_local
  use core_kinds, only: rk, ik, i8
  use mesh_global, only: global_mesh_t, NAME_LEN
  use mesh_geometry, only: HEX_FACE_NODES
  use parallel_env, only: par_rank
  use parallel_halo, only: halo_t
  use parallel_redistribute, only: redistribute_t
  implicit none
  private
  public :: mesh_build_local

  !> Local mesh. Owned items come first, each group sorted by global id.
  type, public :: mesh_t
    integer :: nnode = 0 !< local nodes (owned + ghost)
    integer :: nnode_owned = 0 !< nodes 1..nnode_owned are owned
    integer :: nzone = 0 !< local zones (owned + ghost)
    integer :: nzone_owned = 0 !< zones 1..nzone_owned are owned
    integer(i8) :: nnode_global = 0 !< nodes of the whole mesh
    integer(i8) :: nzone_global = 0 !< zones of the whole mesh
    integer(i8), allocatable :: node_gid(:) !< 1-based global node ids
    integer(i8), allocatable :: zone_gid(:) !< 1-based global zone ids
    integer, allocatable :: node_owner(:) !< owner rank of each local node
    integer, allocatable :: zone_node(:, :) !< (8, nzone) local node indices
    integer, allocatable :: zone_block(:) !< block index of each zone
    integer, allocatable :: corner_start(:) !< CSR over owned nodes, size nnode_owned+1
    integer, allocatable :: corner_list(:) !< corner 8 (z-1) + c, sorted by zone global id
    integer, allocatable :: face_neighbour(:, :) !< (6, nzone) zone across each face:
        !< local index, 0 on the mesh boundary, -1 when the neighbour is not local
    integer, allocatable :: face_neighbour_face(:, :) !< (6, nzone) the neighbour's face
    integer :: nset = 0 !< face sets
    character(len=NAME_LEN), allocatable :: set_name(:)
    integer, allocatable :: set_start(:) !< CSR over local faces of each set
    integer, allocatable :: set_zone(:) !< local zone of each face
    integer, allocatable :: set_face(:) !< face 1..6 of that zone
    type(halo_t) :: node_halo !< refresh of ghost node data
    type(halo_t) :: zone_halo !< refresh of ghost zone data (restart, limiter)
    type(redistribute_t) :: node_io !< owned nodes <-> dump blocks
    type(redistribute_t) :: zone_io !< owned zones <-> dump blocks
  end type mesh_t

contains

  !> Build this rank's mesh from the global one and the zone owner array.
  subroutine mesh_build_local(global, part, mesh)
    type(global_mesh_t), intent(in) :: global
    integer(ik), intent(in) :: part(:) !< owner rank of every global zone
    type(mesh_t), intent(inout) :: mesh
    integer :: me, z, c, n, k, i, nz, nn, count_owned, f, s
    integer, allocatable :: adj_start(:), adj_zone(:), fill(:)
    integer, allocatable :: node_owner_global(:), zone_local(:), node_local(:)
    logical, allocatable :: zone_mark(:), node_mark(:)

    me = par_rank()
    nz = global%nzone
    nn = global%nnode
    mesh%nnode_global = nn
    mesh%nzone_global = nz

    ! Global node -> zone adjacency, zones in increasing global id.
    allocate(adj_start(nn + 1), fill(nn))
    adj_start = 0
    do z = 1, nz
      do c = 1, 8
        n = global%connectivity(c, z)
        adj_start(n + 1) = adj_start(n + 1) + 1
      end do
    end do
    adj_start(1) = 1
    do n = 1, nn
      adj_start(n + 1) = adj_start(n + 1) + adj_start(n)
    end do
    allocate(adj_zone(adj_start(nn + 1) - 1))
    fill = adj_start(1:nn)
    do z = 1, nz
      do c = 1, 8
        n = global%connectivity(c, z)
        adj_zone(fill(n)) = z
        fill(n) = fill(n) + 1
      end do
    end do
    ! A node belongs to the owner of its lowest-id zone.
    allocate(node_owner_global(nn))
    do n = 1, nn
      node_owner_global(n) = part(adj_zone(adj_start(n)))
    end do

    ! Local zones: owned, then every zone touching a node of an owned zone.
    allocate(zone_mark(nz))
    zone_mark = .false.
    do z = 1, nz
      if (part(z) /= me) cycle
      do c = 1, 8
        n = global%connectivity(c, z)
        zone_mark(adj_zone(adj_start(n):adj_start(n + 1) - 1)) = .true.
      end do
    end do
    mesh%nzone_owned = count(part == me)
    mesh%nzone = count(zone_mark)
    allocate(mesh%zone_gid(mesh%nzone), zone_local(nz))
    zone_local = 0
    k = 0
    do z = 1, nz
      if (part(z) == me) then
        k = k + 1
        mesh%zone_gid(k) = z
        zone_local(z) = k
      end if
    end do
    do z = 1, nz
      if (zone_mark(z) .and. part(z) /= me) then
        k = k + 1
        mesh%zone_gid(k) = z
        zone_local(z) = k
      end if
    end do

    ! Local nodes: those of local zones, owned first.
    allocate(node_mark(nn))
    node_mark = .false.
    do k = 1, mesh%nzone
      node_mark(global%connectivity(:, mesh%zone_gid(k))) = .true.
    end do
    count_owned = 0
    do n = 1, nn
      if (node_mark(n) .and. node_owner_global(n) == me) count_owned = count_owned + 1
    end do
    mesh%nnode_owned = count_owned
    mesh%nnode = count(node_mark)
    allocate(mesh%node_gid(mesh%nnode), mesh%node_owner(mesh%nnode), node_local(nn))
    node_local = 0
    k = 0
    do n = 1, nn
      if (node_mark(n) .and. node_owner_global(n) == me) then
        k = k + 1
        mesh%node_gid(k) = n
        node_local(n) = k
      end if
    end do
    do n = 1, nn
      if (node_mark(n) .and. node_owner_global(n) /= me) then
        k = k + 1
        mesh%node_gid(k) = n
        node_local(n) = k
      end if
    end do
    do k = 1, mesh%nnode
      mesh%node_owner(k) = node_owner_global(mesh%node_gid(k))
    end do

    allocate(mesh%zone_node(8, mesh%nzone), mesh%zone_block(mesh%nzone))
    do k = 1, mesh%nzone
      z = int(mesh%zone_gid(k))
      mesh%zone_node(:, k) = node_local(global%connectivity(:, z))
      mesh%zone_block(k) = global%zone_block(z)
    end do

    ! Corners of each owned node, in increasing zone global id.
    allocate(mesh%corner_start(mesh%nnode_owned + 1))
    mesh%corner_start(1) = 1
    do k = 1, mesh%nnode_owned
      n = int(mesh%node_gid(k))
      mesh%corner_start(k + 1) = mesh%corner_start(k) + adj_start(n + 1) - adj_start(n)
    end do
    allocate(mesh%corner_list(mesh%corner_start(mesh%nnode_owned + 1) - 1))
    do k = 1, mesh%nnode_owned
      n = int(mesh%node_gid(k))
      i = mesh%corner_start(k)
      do s = adj_start(n), adj_start(n + 1) - 1
        z = adj_zone(s)
        do c = 1, 8
          if (global%connectivity(c, z) == n) exit
        end do
        mesh%corner_list(i) = 8 * (zone_local(z) - 1) + c
        i = i + 1
      end do
    end do

    call build_face_neighbours(global, adj_start, adj_zone, zone_local, mesh)

    ! Face sets restricted to local zones, in global order.
    mesh%nset = global%nset
    allocate(mesh%set_name(mesh%nset), mesh%set_start(mesh%nset + 1))
    mesh%set_name = global%set_name
    k = 0
    do f = 1, global%nset
      do s = global%set_start(f), global%set_start(f + 1) - 1
        if (zone_local(global%set_zone(s)) > 0) k = k + 1
      end do
    end do
    allocate(mesh%set_zone(k), mesh%set_face(k))
    k = 0
    mesh%set_start(1) = 1
    do f = 1, global%nset
      do s = global%set_start(f), global%set_start(f + 1) - 1
        if (zone_local(global%set_zone(s)) > 0) then
          k = k + 1
          mesh%set_zone(k) = zone_local(global%set_zone(s))
          mesh%set_face(k) = global%set_face(s)
        end if
      end do
      mesh%set_start(f + 1) = k + 1
    end do

    call mesh%node_halo%init(mesh%node_gid, mesh%node_owner, mesh%nnode_owned)
    call mesh%zone_halo%init(mesh%zone_gid, [(int(part(mesh%zone_gid(k))), k = 1, mesh%nzone)], &
        mesh%nzone_owned)
    call mesh%node_io%init(mesh%node_gid(1:mesh%nnode_owned), mesh%nnode_global)
    call mesh%zone_io%init(mesh%zone_gid(1:mesh%nzone_owned), mesh%nzone_global)
  end subroutine mesh_build_local

  !> Zone across each face of every local zone (same four nodes).
  subroutine build_face_neighbours(global, adj_start, adj_zone, zone_local, mesh)
    type(global_mesh_t), intent(in) :: global
    integer, intent(in) :: adj_start(:), adj_zone(:), zone_local(:)
    type(mesh_t), intent(inout) :: mesh
    integer :: k, z, f, s, s2, other, g, nodes(4), onodes(4)
    allocate(mesh%face_neighbour(6, mesh%nzone), mesh%face_neighbour_face(6, mesh%nzone))
    mesh%face_neighbour = 0
    mesh%face_neighbour_face = 0
    do k = 1, mesh%nzone
      z = int(mesh%zone_gid(k))
      do f = 1, 6
        nodes = global%connectivity(HEX_FACE_NODES(:, f), z)
        do s = adj_start(nodes(1)), adj_start(nodes(1) + 1) - 1
          other = adj_zone(s)
          if (other == z) cycle
          do g = 1, 6
            onodes = global%connectivity(HEX_FACE_NODES(:, g), other)
            if (all([(any(onodes == nodes(s2)), s2 = 1, 4)])) then
              mesh%face_neighbour(f, k) = zone_local(other)
              if (zone_local(other) == 0) mesh%face_neighbour(f, k) = -1
              mesh%face_neighbour_face(f, k) = g
            end if
          end do
        end do
      end do
    end do
  end subroutine build_face_neighbours

end module mesh_local
