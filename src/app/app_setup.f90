!> Set-up of a run: the restart's checks, mesh, partition, blocks,
!> boundaries, initial state, contact, the restart read.
module app_setup
  use, intrinsic :: iso_fortran_env, only: output_unit
  use core_kinds, only: rk, ik, i8
  use core_status, only: status_t
  use core_timer, only: timers_t
  use core_names, only: name_hint
  use core_memory, only: peak_memory_mb
  use mesh_geometry, only: hex_centroid
  use mesh_global, only: global_mesh_t, mesh_make_box, mesh_append, NAME_LEN
  use mesh_import, only: mesh_import_file, mesh_import_group_kind, mesh_import_summary
  use mesh_exodus, only: exodus_part_t, exodus_scan, range_add_exodus
  use mesh_gmsh_stream, only: gmsh_part_t, gmsh_scan, range_add_gmsh
  use mesh_curved, only: curved_part
  use mesh_blocks, only: block_part_t, part_assemble, range_add_part, part_set_counts
  use mesh_local, only: mesh_t
  use mesh_range, only: mesh_range_t, range_init, range_add_box, range_add_global, &
      range_set_index, box_sizes, box_set_counts
  use mesh_distribute, only: mesh_distribute_build, distribute_stats_t
  use contact_surface, only: set_names_of
  use hydro_state, only: state_t, state_init, HOURGLASS_STIFFNESS, HOURGLASS_NONE
  use hydro_boundary, only: boundary_t, boundary_setup, boundary_constrain, boundary_prescribed, &
      BC_SYMMETRY, BC_WALL
  use hydro_initial, only: initial_apply
  use hydro_driver, only: material_zones_t, material_zones_build
  use hydro_erosion, only: erosion_allocate, erosion_restore
  use solver_step, only: solver_contact_refresh
  use contact_enforce, only: contact_t, contact_setup, side_context_t, contact_active_restore, &
      contact_offset_restore, &
      contact_resume_state, contact_resume
  use contact_monitor, only: contact_initial
  use contact_state, only: initial_offsets_t
  use io_deck, only: config_t
  use io_dump, only: dump_read
  use io_probe, only: probes_t, probe_setup
  use app_provenance, only: restart_deck_check
  use material_table, only: STRENGTH_NONE
  use parallel_env, only: par_size, par_rank, par_bcast, par_sum, par_max, par_allgather
  use parallel_route, only: par_max_i8
  implicit none
  private
  public :: setup_run, setup_mesh, setup_state, assign_blocks, setup_sides

  !> A curved part of a deck (the array of them is one per &mesh part).
  type :: block_part_holder_t
    class(block_part_t), allocatable :: part
  end type block_part_holder_t

  !> The &block of each volume group of an imported part.
  type :: group_map_t
    integer, allocatable :: block(:)
  end type group_map_t

contains

  !> Everything between the deck and the first cycle that input can make
  !> fail, in order: a restart file's existence and its stored deck against
  !> this one (before anything else), the mesh, initial contact overlaps (may
  !> move nodes: before the nodal masses), the state, the contact set-up, the
  !> probes, the restart read (section 'restart read' of timers). Problems
  !> go to status.
  subroutine setup_run(config, restart, force, mesh, bc, state, mz, ct, probes, timers, status)
    type(config_t), intent(in) :: config
    character(len=*), intent(in) :: restart !< restart dump, '' for a new run
    logical, intent(in) :: force !< restart even if groups that must not change did
    type(mesh_t), intent(out) :: mesh
    type(boundary_t), intent(out) :: bc
    type(state_t), intent(out) :: state
    type(material_zones_t), intent(out) :: mz
    type(contact_t), intent(out) :: ct
    type(probes_t), intent(out) :: probes
    type(timers_t), intent(inout) :: timers
    type(status_t), intent(inout) :: status
    type(global_mesh_t) :: global
    type(initial_offsets_t), allocatable :: offsets(:)
    real(rk), allocatable :: coordinates(:, :)
    real(rk), allocatable :: pair_work(:), active(:), resume(:), offset_values(:, :)
    type(side_context_t) :: sides
    logical :: exists
    if (len_trim(restart) > 0) then
      exists = .false.
      if (par_rank() == 0) inquire(file=restart, exist=exists)
      call par_bcast(exists)
      if (.not. exists) call status%add('&control: restart: file '''//trim(restart)// &
          ''' does not exist')
      if (status%ok()) call restart_deck_check(restart, config, force, status)
    end if
    if (status%ok()) call setup_mesh(config, global, mesh, coordinates, bc, timers, status)
    if (.not. status%ok()) return
    sides = setup_sides(config)
    if (size(config%contacts) > 0) then
      call timers%start('contact set-up')
      ! (initial overlaps may move nodes)
      call contact_initial(config%contacts, mesh, coordinates, bc%symmetry_planes, offsets, &
          status, sides)
      call timers%stop('contact set-up')
    end if
    if (status%ok()) call setup_state(config, coordinates, mesh, bc, state, mz, status)
    if (status%ok()) call probe_setup(config%probes, mesh, coordinates, &
        config%output%directory, config%units, probes, status)
    if (status%ok()) then
      call timers%start('contact set-up')
      call contact_setup(config%contacts, mesh, state%node_position, state%node_mass, &
          ct, status, offsets, bc%symmetry_planes, boundary_prescribed(bc, &
          size(state%node_mass)), sides)
      call timers%stop('contact set-up')
    end if
    if (.not. status%ok()) return
    call global%free()
    if (len_trim(restart) > 0) then
      call timers%start('restart read')
      ! The contact work (and each interface's) goes on from the dump's.
      pair_work = ct%pairs(:)%work
      allocate(active(mesh%nnode))
      resume = contact_resume_state(ct)
      allocate(offset_values(ct%ndeck, mesh%nnode))
      call dump_read(restart, mesh, state, status, ct%work, pair_work, active, resume, &
          offset_values)
      ct%pairs(:)%work = pair_work
      call timers%stop('restart read')
      if (.not. status%ok()) return
    end if
    ! The positions at t = 0 (a restart has them from its dump): the dumps'
    ! displacement, the initial volumes of the distortion erosion.
    if (.not. allocated(state%node_position_initial)) &
        state%node_position_initial = state%node_position
    call erosion_restore(mesh, state, mz, config%erosion)
    if (len_trim(restart) > 0) then
      ! A restart after an erosion: the contact surfaces of the live zones;
      ! then the contact's restart state of the dump, offsets measured when
      ! nodes joined included.
      if (allocated(state%zone_alive)) then
        if (par_sum(count(state%zone_alive(1:mesh%nzone_owned) == 0.0_rk)) > 0) &
            call solver_contact_refresh(mesh, state, bc, ct, sides, timers)
      end if
      call contact_active_restore(ct, active)
      call contact_offset_restore(ct, offset_values)
      call contact_resume(ct, resume)
    end if
  end subroutine setup_run

  !> The block of a zone whose centroid is c: the last block whose box holds
  !> it, blocks marked taken excepted (0 = none).
  integer function block_at(config, c, taken) result(block)
    type(config_t), intent(in) :: config
    real(rk), intent(in) :: c(3)
    logical, intent(in) :: taken(:) !< per &block
    integer :: b
    block = 0
    do b = 1, size(config%blocks)
      if (taken(b)) cycle
      associate(box => config%blocks(b)%box)
        if (c(1) >= box(1) .and. c(1) <= box(2) .and. c(2) >= box(3) .and. &
            c(2) <= box(4) .and. c(3) >= box(5) .and. c(3) <= box(6)) block = b
      end associate
    end do
  end function block_at

  !> Each zone of this rank's range not yet in a block belongs to the last
  !> block whose box holds its centroid; blocks marked in claimed (named after
  !> a volume group of an imported mesh file: they belong to that part) are
  !> not candidates. The count of zones in no block is over all ranks.
  subroutine assign_blocks(config, range, status, claimed)
    type(config_t), intent(in) :: config
    type(mesh_range_t), intent(inout) :: range
    type(status_t), intent(inout) :: status
    logical, intent(in) :: claimed(:) !< per &block
    integer :: z
    integer(i8) :: missing
    character(len=32) :: text
    missing = 0
    do z = 1, range%nzone
      if (range%zone_block(z) /= 0) cycle
      range%zone_block(z) = block_at(config, hex_centroid(range%corner_x(:, :, z)), claimed)
      if (range%zone_block(z) == 0) missing = missing + 1
    end do
    missing = par_sum(missing)
    if (missing > 0) then
      write(text, '(i0)') missing
      if (any(claimed)) then
        call status%add('&block: box: '//trim(text)//' zones lie in no block''s box '// &
            '(every zone needs a block; a &block named after a physical volume or element '// &
            'block of a mesh file holds that part''s zones only)')
      else
        call status%add('&block: box: '//trim(text)//' zones lie in no block''s box '// &
            '(every zone needs a block)')
      end if
    end if
  end subroutine assign_blocks

  !> Imported meshes: the volume group (Gmsh physical volume, Exodus element
  !> block) of each zone names its &block, which is then claimed by this part.
  subroutine assign_blocks_by_name(config, where, kind, path, group_names, global, claimed, &
      status)
    type(config_t), intent(in) :: config
    character(len=*), intent(in) :: where !< '&mesh' or '&mesh(k)'
    character(len=*), intent(in) :: kind !< what the file calls a volume group, for messages
    character(len=*), intent(in) :: path !< the mesh file, for messages
    character(len=*), intent(in) :: group_names(:)
    type(global_mesh_t), intent(inout) :: global
    logical, intent(inout) :: claimed(:) !< per &block
    type(status_t), intent(inout) :: status
    integer, allocatable :: map(:)
    integer :: g, z
    call group_block_map(config, where, kind, path, group_names, [(any(global%zone_block == g), &
        g = 1, size(group_names))], claimed, map, status)
    if (.not. status%ok()) return
    do z = 1, global%nzone
      global%zone_block(z) = map(global%zone_block(z))
    end do
  end subroutine assign_blocks_by_name

  !> map(g): the &block named after volume group g of an imported part (0 =
  !> none: a problem if the group holds zones); the blocks of groups with
  !> zones are claimed by this part.
  subroutine group_block_map(config, where, kind, path, group_names, used, claimed, map, status)
    type(config_t), intent(in) :: config
    character(len=*), intent(in) :: where, kind, path
    character(len=*), intent(in) :: group_names(:)
    logical, intent(in) :: used(:) !< group g holds zones
    logical, intent(inout) :: claimed(:) !< per &block
    integer, allocatable, intent(out) :: map(:)
    type(status_t), intent(inout) :: status
    integer :: g, b
    allocate(map(size(group_names)))
    map = 0
    do g = 1, size(group_names)
      do b = 1, size(config%blocks)
        if (config%blocks(b)%name == group_names(g)) map(g) = b
      end do
      if (map(g) == 0 .and. used(g)) call status%add(trim(where)// &
          ': file: the '//kind//' '''//trim(group_names(g))//''' of mesh file '''//path// &
          ''' has no &block of that name'//name_hint(group_names(g), config%blocks%name))
      if (map(g) > 0 .and. used(g)) claimed(map(g)) = .true.
    end do
  end subroutine group_block_map

  !> Build this rank's mesh: every &mesh part in deck order, each rank
  !> generating only its contiguous range of the global zone ids (box and
  !> curved parts zone by zone; imported parts are still read whole on every
  !> rank and cut to the range), blocks, the parallel partition and the
  !> distribution (mesh_distribute), the boundaries and the contact surfaces'
  !> names. coordinates are the local nodes' initial positions. With whole,
  !> the whole mesh is also built in global from the same parts (tests that
  !> compare with a brute force over the whole mesh; never in a run).
  subroutine setup_mesh(config, global, mesh, coordinates, bc, timers, status, whole)
    type(config_t), intent(in) :: config
    type(global_mesh_t), intent(inout) :: global
    type(mesh_t), intent(inout) :: mesh
    real(rk), allocatable, intent(out) :: coordinates(:, :) !< (3, mesh%nnode)
    type(boundary_t), intent(inout) :: bc
    type(timers_t), intent(inout) :: timers
    type(status_t), intent(inout) :: status
    !> build the whole mesh in global too (tests comparing with a brute
    !> force over the whole mesh)
    logical, intent(in), optional :: whole
    character(len=NAME_LEN), allocatable :: group_names(:)
    type(global_mesh_t), allocatable :: pieces(:)
    type(block_part_holder_t), allocatable :: curved(:)
    type(exodus_part_t), allocatable :: exodus(:)
    type(gmsh_part_t), allocatable :: gmsh(:)
    type(group_map_t), allocatable :: maps(:)
    type(mesh_range_t) :: range
    type(distribute_stats_t) :: stats
    integer :: k, n, b, nx, ny, nz, lo, hi, z, m, count_before
    integer(i8) :: nzone, nnode, zone0, node0
    integer, allocatable :: sets(:, :)
    integer(i8), allocatable :: ord0(:, :), counts(:)
    character(len=16) :: where
    character(len=200), allocatable :: lines(:)
    character(len=:), allocatable :: imported
    logical :: claimed(size(config%blocks)), need_global, is_box, is_curved
    integer :: part_block(size(config%parts))

    claimed = .false.
    imported = ''
    need_global = .false.
    if (present(whole)) need_global = whole
    call global%free()
    allocate(global%coordinates(3, 0), global%connectivity(8, 0), global%zone_block(0))
    call timers%start('mesh generate')
    ! Imported parts are read whole (with their blocks, rotation and offset);
    ! boxes and curved parts only counted (built whole too for tests, whole).
    allocate(pieces(size(config%parts)), curved(size(config%parts)))
    allocate(exodus(size(config%parts)), maps(size(config%parts)), gmsh(size(config%parts)))
    nzone = 0
    nnode = 0
    part_block = 0
    do k = 1, size(config%parts)
      associate(spec => config%parts(k), piece => pieces(k))
        where = '&mesh'
        if (size(config%parts) > 1) write(where, '(a,i0,a)') '&mesh(', k, ')'
        if (len_trim(spec%block) > 0) then
          do n = 1, size(config%blocks)
            if (config%blocks(n)%name == spec%block) part_block(k) = n
          end do
          if (part_block(k) == 0) then
            call status%add(trim(where)//': block: '''//trim(spec%block)// &
                ''' is not the name of a &block'//name_hint(spec%block, config%blocks%name))
            return
          end if
        end if
        is_box = .false.
        is_curved = .false.
        select case (spec%mesh_type)
        case ('rod', 'tube', 'shell', 'ball', 'box_minus_ball')
          is_curved = .true.
          call curved_part(spec%mesh_type, spec%rod, spec%tube, spec%shell, spec%ball, &
              spec%box_minus_ball, curved(k)%part, status)
          if (status%ok()) then
            nzone = nzone + curved(k)%part%nzone
            nnode = nnode + curved(k)%part%nnode
            if (need_global) call part_assemble(curved(k)%part, piece)
          end if
        case ('gmsh', 'exodus')
          call import_part()
          if (.not. status%ok()) return
          nzone = nzone + piece%nzone
          nnode = nnode + piece%nnode
          cycle
        case default
          is_box = .true.
          call box_sizes(spec%box, nx, ny, nz)
          if (nx < 1 .or. ny < 1 .or. nz < 1) then
            call status%add('&mesh: the box needs at least one zone in each direction')
            return
          end if
          nzone = nzone + int(nx, i8) * ny * nz
          nnode = nnode + int(nx + 1, i8) * (ny + 1) * (nz + 1)
          if (need_global) call mesh_make_box(spec%box, piece, status)
        end select
        if (.not. status%ok()) return
        if (.not. (is_box .or. is_curved)) then
          nzone = nzone + piece%nzone
          nnode = nnode + piece%nnode
        end if
        if (.not. allocated(piece%coordinates)) cycle
        if (spec%rotation_angle /= 0.0_rk) call rotate(piece%coordinates, &
            spec%rotation_axis, spec%rotation_angle)
        do n = 1, piece%nnode
          piece%coordinates(:, n) = piece%coordinates(:, n) + spec%offset
        end do
        ! Blocks: the part's own block, else its physical volumes (Gmsh), else
        ! the block boxes (after the parts are joined).
        if (part_block(k) > 0) then
          piece%zone_block = int(part_block(k), ik)
        else if (spec%mesh_type == 'gmsh' .or. spec%mesh_type == 'exodus') then
          call assign_blocks_by_name(config, where, mesh_import_group_kind(spec%mesh_type), &
              spec%mesh_path, group_names, piece, claimed, status)
          if (.not. status%ok()) return
          imported = imported//'; '//mesh_import_group_kind(spec%mesh_type)//'s of '''// &
              spec%mesh_path//''':'
          do n = 1, size(group_names)
            if (any(piece%zone_block == n)) imported = imported//' '//trim(group_names(n))
          end do
        else
          piece%zone_block = 0
        end if
      end associate
    end do

    ! This rank's range of the joined parts; sets named as mesh_append names
    ! them (the plain names, then the part's prefixed ones).
    call range_init(range, nzone, nnode)
    zone0 = 0
    node0 = 0
    do k = 1, size(config%parts)
      associate(spec => config%parts(k), piece => pieces(k))
        is_box = spec%mesh_type == 'box'
        where = '&mesh'
        if (size(config%parts) > 1) write(where, '(a,i0,a)') '&mesh(', k, ')'
        if (allocated(curved(k)%part)) then
          counts = part_set_counts(curved(k)%part)
          allocate(sets(2, size(counts)), ord0(2, size(counts)))
          call map_sets(curved(k)%part%set_names)
          call range_add_part(range, curved(k)%part, zone0, node0, sets, ord0, lo, hi)
          call place(lo, hi)
          if (hi >= lo) range%zone_block(lo:hi) = part_block(k)
          zone0 = zone0 + curved(k)%part%nzone
          node0 = node0 + curved(k)%part%nnode
          deallocate(curved(k)%part)
        else if (is_box) then
          call box_sizes(spec%box, nx, ny, nz)
          allocate(counts(6))
          counts = box_set_counts(nx, ny, nz)
          allocate(sets(2, 6), ord0(2, 6))
          call map_sets([character(len=NAME_LEN) :: 'xmin', 'xmax', 'ymin', 'ymax', &
              'zmin', 'zmax'])
          call range_add_box(range, spec%box, zone0, node0, sets, ord0, lo, hi)
          call place(lo, hi)
          if (hi >= lo) range%zone_block(lo:hi) = part_block(k)
          zone0 = zone0 + int(nx, i8) * ny * nz
          node0 = node0 + int(nx + 1, i8) * (ny + 1) * (nz + 1)
        else if (allocated(exodus(k)%path)) then
          ! An Exodus II file read by ranges on every rank.
          counts = exodus(k)%set_size
          allocate(sets(2, exodus(k)%nset), ord0(2, exodus(k)%nset))
          call map_sets(exodus(k)%set_names)
          count_before = status%count
          call range_add_exodus(range, exodus(k), zone0, node0, sets, ord0, lo, hi, &
              trim(where)//': '//trim(spec%mesh_type)//' mesh file '''//spec%mesh_path// &
              ''' read:', lines, status)
          if (par_rank() == 0 .and. status%count == count_before) write(output_unit, '(a)') &
              (trim(lines(n)), n = 1, size(lines))
          if (hi >= lo) range%zone_block(lo:hi) = int(maps(k)%block(range%zone_block(lo:hi)), ik)
          call place(lo, hi)
          zone0 = zone0 + exodus(k)%nelem
          node0 = node0 + exodus(k)%nnode
        else if (allocated(gmsh(k)%path)) then
          ! A Gmsh file streamed by rank 0 in chunks; the sets' sizes come
          ! with the faces.
          allocate(counts(size(gmsh(k)%set_names)))
          counts = 0
          allocate(sets(2, size(counts)), ord0(2, size(counts)))
          call map_sets(gmsh(k)%set_names)
          count_before = status%count
          call range_add_gmsh(range, gmsh(k), zone0, node0, sets, ord0, lo, hi, &
              trim(where)//': '//trim(spec%mesh_type)//' mesh file '''//spec%mesh_path// &
              ''' read:', lines, status)
          do n = 1, size(counts)
            do m = 1, 2
              if (sets(m, n) > 0) range%set_count(sets(m, n)) = range%set_count(sets(m, n)) + &
                  gmsh(k)%set_count(n)
            end do
          end do
          if (par_rank() == 0 .and. status%count == count_before) write(output_unit, '(a)') &
              (trim(lines(n)), n = 1, size(lines))
          if (hi >= lo .and. status%ok()) range%zone_block(lo:hi) = &
              int(maps(k)%block(range%zone_block(lo:hi)), ik)
          call place(lo, hi)
          zone0 = zone0 + gmsh(k)%nhex
          node0 = node0 + gmsh(k)%nnode
        else
          allocate(counts(piece%nset))
          counts = int(piece%set_start(2:) - piece%set_start(:piece%nset), i8)
          allocate(sets(2, piece%nset), ord0(2, piece%nset))
          call map_sets(piece%set_name(:piece%nset))
          ! (only with the whole mesh: a part read whole on every rank)
          call range_add_global(range, piece, zone0, node0, sets, ord0, lo, hi)
          zone0 = zone0 + piece%nzone
          node0 = node0 + piece%nnode
        end if
        if (need_global) call mesh_append(global, piece, trim(spec%name))
        call piece%free()
        deallocate(counts, sets, ord0)
      end associate
    end do
    call timers%stop('mesh generate')
    call read_memory_report()
    call assign_blocks(config, range, status, claimed)
    if (need_global) then
      do z = 1, global%nzone
        if (global%zone_block(z) == 0) global%zone_block(z) = block_at(config, &
            hex_centroid(global%coordinates(:, global%connectivity(:, z))), claimed)
      end do
    end if
    if (.not. status%ok()) return
    ! With imported parts, a &block that holds no zone is a misspelt name.
    if (len(imported) > 0) then
      do b = 1, size(config%blocks)
        if (par_max(merge(1, 0, any(range%zone_block == b))) > 0) cycle
        write(where, '(a,i0,a)') '&block(', b, ')'
        call status%add(trim(where)//': name: '''//trim(config%blocks(b)%name)//''' holds '// &
            'no zone: it names no volume group of the mesh files ('//imported(3:)// &
            '), no &mesh part''s block, and its box holds no zone of the other parts')
      end do
      if (.not. status%ok()) return
    end if
    call mesh_distribute_build(range, config%partitioner, mesh, coordinates, stats, timers)
    call partition_report(mesh, stats)
    call boundary_setup(config%boundaries, mesh, coordinates, bc, status)
    call check_contacts(config, mesh, status)

  contains

    !> Imported part k, first pass (collective): an Exodus II file scanned by
    !> ranges on every rank, a Gmsh file streamed by rank 0; every rank then
    !> has the same problems, the blocks the part claims (maps(k)) and its
    !> sizes, and range_add_exodus or range_add_gmsh reads the zones into the
    !> range later. With the whole mesh wanted (tests), every rank reads the
    !> file whole, places it and gives its zones blocks by group name.
    subroutine import_part()
      integer :: count0
      count0 = status%count
      associate(spec => config%parts(k), piece => pieces(k))
        if (spec%mesh_type == 'exodus' .and. .not. need_global) then
          ! Every rank reads its ranges (exodus_scan now, range_add_exodus later).
          call exodus_scan(spec%mesh_path, exodus(k), status)
          if (status%count > count0) return
          associate(x => exodus(k))
            if (part_block(k) > 0) then
              allocate(maps(k)%block(x%nblock))
              maps(k)%block = part_block(k)
            else
              call group_block_map(config, where, mesh_import_group_kind(spec%mesh_type), &
                  spec%mesh_path, x%block_names, x%block_start(2:) > x%block_start(:x%nblock), &
                  claimed, maps(k)%block, status)
              imported = imported//'; '//mesh_import_group_kind(spec%mesh_type)//'s of '''// &
                  spec%mesh_path//''':'
              do n = 1, x%nblock
                if (x%block_start(n + 1) > x%block_start(n)) imported = imported//' '// &
                    trim(x%block_names(n))
              end do
            end if
            piece%nzone = x%nelem
            piece%nnode = int(x%nnode)
            piece%nset = x%nset
          end associate
          return
        end if
        if (spec%mesh_type == 'gmsh' .and. .not. need_global) then
          ! Rank 0 streams the file in chunks (gmsh_scan now, range_add_gmsh later).
          call gmsh_scan(spec%mesh_path, gmsh(k), status)
          if (status%count > count0) return
          associate(x => gmsh(k))
            if (part_block(k) > 0) then
              allocate(maps(k)%block(size(x%block_tags)))
              maps(k)%block = part_block(k)
            else
              call group_block_map(config, where, mesh_import_group_kind(spec%mesh_type), &
                  spec%mesh_path, x%block_names, x%block_used, claimed, maps(k)%block, status)
              imported = imported//'; '//mesh_import_group_kind(spec%mesh_type)//'s of '''// &
                  spec%mesh_path//''':'
              do n = 1, size(x%block_tags)
                if (x%block_used(n)) imported = imported//' '//trim(x%block_names(n))
              end do
            end if
            piece%nzone = int(x%nhex)
            piece%nnode = int(x%nnode)
            piece%nset = size(x%set_tags)
          end associate
          return
        end if
        if (need_global) then
          call mesh_import_file(spec%mesh_type, spec%mesh_path, piece, group_names, status)
          if (status%count == count0) then
            if (par_rank() == 0) then
              call mesh_import_summary(piece, group_names, trim(where)//': '// &
                  trim(spec%mesh_type)//' mesh file '''//spec%mesh_path//''' read:', lines)
              write(output_unit, '(a)') (trim(lines(n)), n = 1, size(lines))
            end if
            if (spec%rotation_angle /= 0.0_rk) call rotate(piece%coordinates, &
                spec%rotation_axis, spec%rotation_angle)
            do n = 1, piece%nnode
              piece%coordinates(:, n) = piece%coordinates(:, n) + spec%offset
            end do
            if (part_block(k) > 0) then
              piece%zone_block = int(part_block(k), ik)
            else
              call assign_blocks_by_name(config, where, mesh_import_group_kind( &
                  spec%mesh_type), spec%mesh_path, group_names, piece, claimed, status)
              imported = imported//'; '//mesh_import_group_kind(spec%mesh_type)//'s of '''// &
                  spec%mesh_path//''':'
              do n = 1, size(group_names)
                if (any(piece%zone_block == n)) imported = imported//' '//trim(group_names(n))
              end do
            end if
          end if
        end if
      end associate
    end subroutine import_part

    !> The part's rotation and offset on the range's zones lo..hi.
    subroutine place(lo, hi)
      integer, intent(in) :: lo, hi
      integer :: zz, c
      do zz = lo, hi
        if (config%parts(k)%rotation_angle /= 0.0_rk) call rotate(range%corner_x(:, :, zz), &
            config%parts(k)%rotation_axis, config%parts(k)%rotation_angle)
        do c = 1, 8
          range%corner_x(:, c, zz) = range%corner_x(:, c, zz) + config%parts(k)%offset
        end do
      end do
    end subroutine place

    !> sets/ord0 of the part's sets called names: the range's plain-name set
    !> and, with a part name, the prefixed set; the faces before this part.
    subroutine map_sets(names)
      character(len=*), intent(in) :: names(:)
      integer :: i
      sets = 0
      ord0 = 0
      do i = 1, size(names)
        sets(1, i) = range_set_index(range, names(i))
      end do
      if (len_trim(config%parts(k)%name) > 0) then
        do i = 1, size(names)
          sets(2, i) = range_set_index(range, trim(config%parts(k)%name)//'_'//trim(names(i)))
        end do
      end if
      do i = 1, size(names)
        do m = 1, 2
          if (sets(m, i) == 0) cycle
          ord0(m, i) = range%set_count(sets(m, i))
          range%set_count(sets(m, i)) = range%set_count(sets(m, i)) + counts(i)
        end do
      end do
    end subroutine map_sets

  end subroutine setup_mesh

  !> One line on the peak memory of the ranks once the mesh is generated or
  !> read (each rank holding its range of the zones, before partitioning):
  !> what reading a mesh file costs the ranks, rank 0 included.
  subroutine read_memory_report()
    real(rk) :: mine(1)
    real(rk), allocatable :: all(:, :)
    mine(1) = peak_memory_mb()
    allocate(all(1, par_size()))
    call par_allgather(mine, all)
    if (par_rank() == 0) write(output_unit, '(a,f0.1,a,f0.1,a,i0,a)') &
        'mesh read: peak memory per rank (VmHWM) so far: rank 0 ', all(1, 1), ' MB, largest ', &
        maxval(all(1, :)), ' MB (rank ', maxloc(all(1, :), dim=1) - 1, ')'
  end subroutine read_memory_report

  !> One line on the partition: parts, faces cut, the largest rank's zones
  !> over the mean, ghost nodes and set-up bytes sent (largest rank).
  subroutine partition_report(mesh, stats)
    type(mesh_t), intent(in) :: mesh
    type(distribute_stats_t), intent(in) :: stats
    integer :: largest, ghosts
    integer(i8) :: bytes
    real(rk) :: imbalance
    largest = par_max(mesh%nzone_owned)
    ghosts = par_max(mesh%nnode - mesh%nnode_owned)
    bytes = par_max_i8(stats%bytes_sent)
    imbalance = real(largest, rk) * par_size() / real(mesh%nzone_global, rk) - 1.0_rk
    if (par_rank() == 0 .and. par_size() > 1) write(output_unit, '(a,i0,a,i0,a,f0.2,a,i0,a,f0.2,a)') &
        'partition: ', par_size(), ' parts, edge cut ', stats%edge_cut, ' faces, imbalance ', &
        100.0_rk * imbalance, '%, ghost nodes per rank <= ', ghosts, ', set-up sent <= ', &
        real(bytes, rk) / 1.0e6_rk, ' MB per rank'
  end subroutine partition_report

  !> Rotate points about the origin by angle (degrees, right-handed) about
  !> axis (Rodrigues' formula).
  subroutine rotate(x, axis, angle)
    real(rk), intent(inout) :: x(:, :)
    real(rk), intent(in) :: axis(3), angle
    real(rk) :: k(3), c, s, p(3)
    integer :: n
    k = axis / norm2(axis)
    c = cos(angle * acos(-1.0_rk) / 180.0_rk)
    s = sin(angle * acos(-1.0_rk) / 180.0_rk)
    do n = 1, size(x, 2)
      p = x(:, n)
      x(:, n) = p * c + s * [k(2) * p(3) - k(3) * p(2), k(3) * p(1) - k(1) * p(3), &
          k(1) * p(2) - k(2) * p(1)] + k * dot_product(k, p) * (1.0_rk - c)
    end do
  end subroutine rotate

  !> &contact pairs: their surfaces must be face sets of the mesh, checked
  !> here with the other set-up problems before any work; contact_setup
  !> (src/contact) builds the interfaces afterwards.
  subroutine check_contacts(config, mesh, status)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    type(status_t), intent(inout) :: status
    integer :: k
    character(len=16) :: where
    do k = 1, size(config%contacts)
      write(where, '(a,i0,a)') '&contact(', k, ')'
      call check_list('surface_a', config%contacts(k)%surface_a)
      call check_list('surface_b', config%contacts(k)%surface_b)
    end do

  contains

    subroutine check_list(key, list)
      character(len=*), intent(in) :: key, list
      character(len=NAME_LEN), allocatable :: names(:)
      integer :: i
      names = set_names_of(list)
      if (size(names) == 0) call status%add(trim(where)//': '//key//': no face set named')
      do i = 1, size(names)
        ! (block:NAME entries: contact_setup checks the block names)
        if (index(names(i), 'block:') == 1) cycle
        if (.not. any(mesh%set_name == names(i))) call status%add(trim(where)//': '//key//': '''// &
            trim(names(i))//''' is not a face set of the mesh'//name_hint(names(i), &
            mesh%set_name(1:mesh%nset)))
      end do
    end subroutine check_list

  end subroutine check_contacts

  !> Surfaces given by blocks: the deck's blocks, and the face sets that
  !> never form one (symmetry planes, rigid walls); set-up and the contact
  !> refresh after an erosion take the same.
  function setup_sides(config) result(sides)
    type(config_t), intent(in) :: config
    type(side_context_t) :: sides
    sides%block_names = config%blocks(:)%name
    sides%closed_sets = pack(config%boundaries(:)%set, config%boundaries(:)%kind == BC_SYMMETRY &
        .or. config%boundaries(:)%kind == BC_WALL)
  end function setup_sides

  !> Allocate the state and apply the initial conditions (positions of the
  !> local nodes given); nodal masses are the sums of corner masses m_z / 8.
  subroutine setup_state(config, coordinates, mesh, bc, state, mz, status)
    type(config_t), intent(in) :: config
    real(rk), intent(in) :: coordinates(:, :) !< (3, mesh%nnode)
    type(mesh_t), intent(inout) :: mesh
    type(boundary_t), intent(in) :: bc
    type(state_t), intent(inout) :: state
    type(material_zones_t), intent(out) :: mz
    type(status_t), intent(inout) :: status
    integer, allocatable :: zone_material(:)
    integer :: n, z, j
    real(rk) :: m
    call state_init(state, mesh%nnode, mesh%nzone, config%hydro%hourglass == HOURGLASS_STIFFNESS, &
        any(config%materials%strength /= STRENGTH_NONE), &
        hourglass=config%hydro%hourglass /= HOURGLASS_NONE)
    call erosion_allocate(mesh, state, config%failures, config%erosion)
    state%node_position = coordinates
    allocate(zone_material(mesh%nzone))
    do z = 1, mesh%nzone
      zone_material(z) = config%blocks(mesh%zone_block(z))%material
    end do
    call material_zones_build(zone_material, size(config%materials), mz)
    call initial_apply(config%regions, config%materials, zone_material, mesh, state, status, &
        config%blocks%name)
    if (.not. status%ok()) return
    do n = 1, mesh%nnode_owned
      m = 0.0_rk
      do j = mesh%corner_start(n), mesh%corner_start(n + 1) - 1
        m = m + 0.125_rk * state%zone_mass((mesh%corner_list(j) - 1) / 8 + 1)
      end do
      state%node_mass(n) = m
    end do
    ! Boundary velocities hold from t = 0 (a piston moves from the start).
    call boundary_constrain(bc, state%node_velocity, .true.)
    call mesh%node_halo%exchange(state%node_velocity)
  end subroutine setup_state

end module app_setup
