!> The two sides of a contact group as surfaces: named face sets of the mesh,
!> or 'block:NAME' entries, every exterior face of the live zones of those
!> blocks (contact_surface_rebuild on each rank's local mesh, the faces then
!> gathered in global face order). The same block list on both sides is
!> single-surface self-contact.
module contact_sides
  use core_kinds, only: rk, ik, i8
  use core_sort, only: sort_order
  use core_status, only: status_t
  use mesh_global, only: NAME_LEN
  use mesh_geometry, only: HEX_FACE_NODES
  use core_names, only: name_hint
  use mesh_local, only: mesh_t
  use contact_surface, only: contact_surface_t, surface_from_segments, set_names_of, &
      contact_surface_rebuild
  use parallel_env, only: par_allgather, par_max, par_size
  implicit none
  private
  public :: side_is_blocks, side_surface, blocks_of, block_faces

  !> Prefix of a block entry in a surface list.
  character(len=*), parameter, public :: BLOCK_PREFIX = 'block:'

  !> What a block surface needs besides the local mesh.
  type, public :: side_context_t
    character(len=NAME_LEN), allocatable :: block_names(:) !< the deck's blocks, in order
    !> face sets of the local mesh whose faces never form a surface (symmetry
    !> planes, rigid walls)
    character(len=NAME_LEN), allocatable :: closed_sets(:)
  end type side_context_t

contains

  !> Whether a surface list names blocks ('block:al'); a list is all blocks
  !> or all face sets.
  logical function side_is_blocks(list)
    character(len=*), intent(in) :: list
    character(len=NAME_LEN), allocatable :: names(:)
    names = set_names_of(list)
    side_is_blocks = .false.
    if (size(names) > 0) side_is_blocks = index(names(1), BLOCK_PREFIX) == 1
  end function side_is_blocks

  !> Block indices of a block list (problems to status, named by where).
  subroutine blocks_of(list, context, where, blocks, status)
    character(len=*), intent(in) :: list, where
    type(side_context_t), intent(in) :: context
    integer, allocatable, intent(out) :: blocks(:)
    type(status_t), intent(inout) :: status
    character(len=NAME_LEN), allocatable :: names(:)
    integer :: i, b
    names = set_names_of(list)
    allocate(blocks(size(names)))
    blocks = 0
    do i = 1, size(names)
      if (index(names(i), BLOCK_PREFIX) /= 1) then
        call status%add(where//': '''//trim(names(i))//''': a surface is either face sets '// &
            'or blocks (block:NAME), not both')
        cycle
      end if
      do b = 1, size(context%block_names)
        if (context%block_names(b) == names(i)(len(BLOCK_PREFIX) + 1:)) blocks(i) = b
      end do
      if (blocks(i) == 0) call status%add(where//': '''//trim(names(i))//''': no block '''// &
          trim(names(i)(len(BLOCK_PREFIX) + 1:))//'''')
    end do
  end subroutine blocks_of

  !> The exterior faces of blocks (live zones) on the whole mesh, on every
  !> rank: each rank's faces (contact_surface_rebuild) gathered and put in
  !> global face order. facing: blocks across which faces are exterior too.
  !> Collective.
  subroutine block_faces(mesh, live, blocks, facing, context, ids, nodes)
    type(mesh_t), intent(in) :: mesh
    logical, intent(in) :: live(:) !< (nzone local) zone live (ghosts from the zone halo)
    integer, intent(in) :: blocks(:), facing(:)
    type(side_context_t), intent(in) :: context
    integer(i8), allocatable, intent(out) :: ids(:) !< (n) (zone - 1) * 6 + face, ascending
    integer(ik), allocatable, intent(out) :: nodes(:, :) !< (4, n) global node ids
    integer(i8), allocatable :: mine(:), my_nodes(:, :), keys(:, :)
    integer, allocatable :: excluded(:)
    integer :: i, s
    allocate(excluded(0))
    do i = 1, size(context%closed_sets)
      do s = 1, mesh%nset
        if (mesh%set_name(s) == context%closed_sets(i)) excluded = [excluded, s]
      end do
    end do
    call contact_surface_rebuild(mesh, live, blocks, facing, excluded, mine, my_nodes)
    allocate(keys(2, size(mine)))
    keys(1, :) = 0
    keys(2, :) = mine
    call gather_faces(keys, mine, my_nodes, ids, nodes)
  end subroutine block_faces

  !> The faces of named face sets, in the order of the list and, within a
  !> set, in the set's global order (the order of the whole mesh's set), on
  !> every rank: each rank's owned zones' faces of the sets, gathered.
  !> Unknown names go to status with the valid ones. Collective.
  subroutine set_faces(mesh, names, where, ids, nodes, status)
    type(mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: names(:) !< face sets, in the surface's order
    character(len=*), intent(in) :: where !< the deck group, for messages
    integer(i8), allocatable, intent(out) :: ids(:) !< (n) (zone - 1) * 6 + face
    integer(ik), allocatable, intent(out) :: nodes(:, :) !< (4, n) global node ids
    type(status_t), intent(inout) :: status
    integer(i8), allocatable :: keys(:, :), mine(:), my_nodes(:, :)
    integer :: sets(size(names)), i, j, n, pass, z
    sets = 0
    do i = 1, size(names)
      do j = 1, mesh%nset
        if (mesh%set_name(j) == names(i)) sets(i) = j
      end do
      if (sets(i) == 0) call status%add(where//': no face set '''//trim(names(i))// &
          ''' in the mesh'//name_hint(names(i), mesh%set_name(:mesh%nset)))
    end do
    if (any(sets == 0)) then
      allocate(ids(0), nodes(4, 0))
      return
    end if
    do pass = 1, 2
      n = 0
      do i = 1, size(names)
        do j = mesh%set_start(sets(i)), mesh%set_start(sets(i) + 1) - 1
          z = mesh%set_zone(j)
          if (z > mesh%nzone_owned) cycle
          n = n + 1
          if (pass == 1) cycle
          keys(:, n) = [int(i, i8), mesh%set_ord(j)]
          mine(n) = (mesh%zone_gid(z) - 1_i8) * 6_i8 + int(mesh%set_face(j), i8)
          my_nodes(:, n) = mesh%node_gid(mesh%zone_node(HEX_FACE_NODES(:, mesh%set_face(j)), z))
        end do
      end do
      if (pass == 1) allocate(keys(2, n), mine(n), my_nodes(4, n))
    end do
    call gather_faces(keys, mine, my_nodes, ids, nodes)
  end subroutine set_faces

  !> Every rank's faces (id and nodes) on every rank, sorted by their keys
  !> (columns, lexicographically; keys are unique). Collective: one
  !> all-gather of fixed-size records (the largest rank's count).
  subroutine gather_faces(keys, mine, my_nodes, ids, nodes)
    integer(i8), intent(in) :: keys(:, :) !< (2, n) sort keys
    integer(i8), intent(in) :: mine(:) !< (n) face ids
    integer(i8), intent(in) :: my_nodes(:, :) !< (4, n) global node ids
    integer(i8), allocatable, intent(out) :: ids(:)
    integer(ik), allocatable, intent(out) :: nodes(:, :)
    integer, parameter :: W = 7 !< key (2), id, 4 nodes
    integer(i8), allocatable :: record(:), all(:, :), all_keys(:, :)
    integer, allocatable :: perm(:)
    integer :: i, n, nmax, r, count
    n = size(mine)
    nmax = par_max(n)
    ! Fixed-size records: the count, then (key, id, 4 nodes) per face.
    allocate(record(1 + W * nmax), all(1 + W * nmax, par_size()))
    record = 0
    record(1) = int(n, i8)
    do i = 1, n
      record(1 + W * (i - 1) + 1:1 + W * i) = [keys(:, i), mine(i), my_nodes(:, i)]
    end do
    call par_allgather(record, all)
    count = int(sum(all(1, :)))
    allocate(all_keys(2, count), ids(count), nodes(4, count))
    count = 0
    do r = 1, size(all, 2)
      do i = 1, int(all(1, r))
        count = count + 1
        all_keys(:, count) = all(1 + W * (i - 1) + 1:1 + W * (i - 1) + 2, r)
        ids(count) = all(1 + W * (i - 1) + 3, r)
        nodes(:, count) = int(all(1 + W * (i - 1) + 4:1 + W * i, r), ik)
      end do
    end do
    call sort_order(all_keys, perm)
    ids = ids(perm)
    nodes = nodes(:, perm)
  end subroutine gather_faces

  !> A side's surface (global node ids): named face sets, or the exterior
  !> faces of blocks (every zone live at set-up), both from each rank's
  !> local mesh. other: the opposite side's list (its blocks are the facing
  !> blocks; the same list is self-contact). Collective.
  subroutine side_surface(list, other, mesh, context, where, surf, status)
    character(len=*), intent(in) :: list, other, where
    type(mesh_t), intent(in) :: mesh
    type(side_context_t), intent(in) :: context
    type(contact_surface_t), intent(inout) :: surf
    type(status_t), intent(inout) :: status
    integer, allocatable :: blocks(:), facing(:)
    integer(i8), allocatable :: ids(:)
    integer(ik), allocatable :: nodes(:, :)
    logical, allocatable :: live(:)
    type(status_t) :: other_status
    integer :: i
    if (.not. side_is_blocks(list)) then
      call set_faces(mesh, set_names_of(list), where, ids, nodes, status)
      call surface_from_segments(nodes, ids, surf=surf)
      return
    end if
    call blocks_of(list, context, where, blocks, status)
    allocate(facing(0))
    if (side_is_blocks(other) .and. other /= list) then
      ! (the other side's problems are reported with the other side)
      call blocks_of(other, context, where, facing, other_status)
      facing = pack(facing, [(all(blocks /= facing(i)), i = 1, size(facing))])
    end if
    if (.not. status%ok()) return
    allocate(live(mesh%nzone))
    live = .true.
    call block_faces(mesh, live, blocks, facing, context, ids, nodes)
    call surface_from_segments(nodes, ids, surf=surf)
  end subroutine side_surface

end module contact_sides
