!> The two sides of a contact group as surfaces: named face sets of the mesh,
!> or 'block:NAME' entries, every exterior face of the live zones of those
!> blocks (contact_surface_rebuild on each rank's local mesh, the faces then
!> gathered in global face order). The same block list on both sides is
!> single-surface self-contact.
module contact_sides
  use core_kinds, only: rk, ik, i8
  use core_sort, only: sort_order
  use core_status, only: status_t
  use mesh_global, only: global_mesh_t, NAME_LEN
  use mesh_local, only: mesh_t
  use contact_surface, only: contact_surface_t, surface_build, surface_from_segments, &
      set_names_of, contact_surface_rebuild
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
    integer(i8), allocatable :: mine(:), my_nodes(:, :), record(:), all(:, :)
    integer, allocatable :: excluded(:), perm(:)
    integer :: i, s, n, nmax, r, count
    allocate(excluded(0))
    do i = 1, size(context%closed_sets)
      do s = 1, mesh%nset
        if (mesh%set_name(s) == context%closed_sets(i)) excluded = [excluded, s]
      end do
    end do
    call contact_surface_rebuild(mesh, live, blocks, facing, excluded, mine, my_nodes)
    n = size(mine)
    nmax = par_max(n)
    ! Fixed-size records: the count, then (id, 4 nodes) per face.
    allocate(record(1 + 5 * nmax), all(1 + 5 * nmax, par_size()))
    record = 0
    record(1) = int(n, i8)
    do i = 1, n
      record(1 + 5 * (i - 1) + 1) = mine(i)
      record(1 + 5 * (i - 1) + 2:1 + 5 * i) = my_nodes(:, i)
    end do
    call par_allgather(record, all)
    count = int(sum(all(1, :)))
    allocate(ids(count), nodes(4, count))
    count = 0
    do r = 1, size(all, 2)
      do i = 1, int(all(1, r))
        count = count + 1
        ids(count) = all(1 + 5 * (i - 1) + 1, r)
        nodes(:, count) = int(all(1 + 5 * (i - 1) + 2:1 + 5 * i, r), ik)
      end do
    end do
    call sort_order(ids, perm)
    ids = ids(perm)
    nodes = nodes(:, perm)
  end subroutine block_faces

  !> A side's surface (global node ids): named face sets of the global
  !> mesh, or the exterior faces of blocks from the local mesh (every zone
  !> live at set-up). other: the opposite side's list (its blocks are the
  !> facing blocks; the same list is self-contact). Collective for blocks.
  subroutine side_surface(list, other, global, mesh, context, where, surf, status)
    character(len=*), intent(in) :: list, other, where
    type(global_mesh_t), intent(in) :: global
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
      call surface_build(global, set_names_of(list), surf, status)
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
    call surface_from_segments(nodes, ids, global%coordinates, surf)
  end subroutine side_surface

end module contact_sides
